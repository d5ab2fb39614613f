shape_set s -desc {-sub {-sphere 0}}
