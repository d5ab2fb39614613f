set s [string repeat a 1000000]
regsub -all a $s [string repeat & 300] r
