set l [lrepeat 4000 [lrepeat 4000 [string repeat x 1000]]]
string length $l
