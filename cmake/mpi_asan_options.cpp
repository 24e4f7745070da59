// Linked only into sanitizer builds of lightmass_rank: Open MPI's components are
// shared objects it loads and unloads again in MPI_Finalize, and what they leave
// allocated is reported from "<unknown module>", which LeakSanitizer can neither
// name nor suppress. Address and UB checks stay on; the server and every other
// program that does not load Open MPI keep leak checking.
extern "C" const char* __asan_default_options() { return "detect_leaks=0"; }
