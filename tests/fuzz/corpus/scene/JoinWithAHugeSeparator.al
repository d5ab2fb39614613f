set s [string repeat x 10000000]
set l [lrepeat 1000 a]
set j [join $l $s]
