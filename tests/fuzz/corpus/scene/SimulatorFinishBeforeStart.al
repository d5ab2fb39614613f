simulator -start 5 -finish 1
