set x [string repeat x 1000000000]
