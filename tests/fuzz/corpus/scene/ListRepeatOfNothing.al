set l [lrepeat 1825500000]
set n [llength $l]
