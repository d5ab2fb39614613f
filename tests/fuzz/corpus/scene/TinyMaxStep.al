simulator -finish 10 -maxstep 1e-300
