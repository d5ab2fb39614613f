view -scale 0
