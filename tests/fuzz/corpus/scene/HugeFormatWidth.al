set s [format %900000000s x]
