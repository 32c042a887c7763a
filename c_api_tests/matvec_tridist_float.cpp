// matvec_tridist.cpp with PQP_REAL = float, as for a user who edited PQP_Compile.h to make it so:
// MatVec.h and TriDist.h must compile warning-free and answer to float's precision.
#define PQP_TEST_FLOAT 1
#include "matvec_tridist.cpp"
