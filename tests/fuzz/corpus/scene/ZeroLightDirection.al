lightsource -dir {0 0 0}
