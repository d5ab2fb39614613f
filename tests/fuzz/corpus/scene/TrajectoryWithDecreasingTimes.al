trajectory tr -points {{0 1 2 3} {2 1 2 3} {1 0 0 0}}
