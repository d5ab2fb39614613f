body b1 -init_pos {1 2 3}
