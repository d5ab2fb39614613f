simulator -finish 1e9
