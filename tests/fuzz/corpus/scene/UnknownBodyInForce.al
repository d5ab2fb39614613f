shape_set box -desc {-sub {-box {1 1 1}}}
force -body qq -y 1
