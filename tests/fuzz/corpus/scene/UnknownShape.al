body b1 -shape nope
