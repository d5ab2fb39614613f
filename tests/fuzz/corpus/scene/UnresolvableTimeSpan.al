simulator -start 1e300 -finish 1.0000000001e300
