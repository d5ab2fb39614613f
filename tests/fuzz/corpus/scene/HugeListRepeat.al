set x [lrepeat 100000000 a]
