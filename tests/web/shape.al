# The shape editor's test (issue 13, seed Figure 4.3): a cube given by its
# eight corners with a ball on top, one shape set, one body made of it.
simulator -finish 1 -step 0.1

shape_set gem -desc {-sub {-pos {0 0 0} -vertices {{-1 -1 -1} {1 -1 -1} {1 1 -1} {-1 1 -1} {-1 -1 1} {1 -1 1} {1 1 1} {-1 1 1}}} -sub {-pos {0 2 0} -sphere 0.5}}

body g -shape gem -init_pos {0 0 0}
