set t [string repeat x 10000000]
set all [concat {*}[lrepeat 300 $t]]
