trajectory tr -points {{0 0 0 0}} -state pos
