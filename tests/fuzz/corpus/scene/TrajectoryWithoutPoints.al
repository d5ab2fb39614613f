trajectory tr -points {}
