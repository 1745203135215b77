/* A shared object that is not a block program: it lacks vs_blockcode_entry (tests/cli). */
int not_a_block_program(void) { return 42; }
