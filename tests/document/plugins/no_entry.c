/* A shared library without the entry symbol. */
__attribute__((visibility("default"))) int not_a_medium(void) { return 42; }
