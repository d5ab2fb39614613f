interp create x
