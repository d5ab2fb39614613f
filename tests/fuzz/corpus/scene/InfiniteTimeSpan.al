simulator -start -1e308 -finish 1e308
