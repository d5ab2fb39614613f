set o [string repeat "\[" 5000]
eval "set x ${o}"
