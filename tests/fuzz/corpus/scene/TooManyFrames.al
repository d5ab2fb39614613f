simulator -finish 1e6 -frames 1e6
