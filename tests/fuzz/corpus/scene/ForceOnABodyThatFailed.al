shape_set box -desc {-sub {-box {1 1 1}}}
body a -shape box -mass 0
force -body a -y 1
