/* one_thread.c - linked into every fuzz target: libFuzzer runs one input at a
 * time, and an OpenMP team for an 8x8 map spends most of each run waking and
 * spinning its threads (a third of fuzz_proc's time), so the targets run one. */
#include <omp.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    omp_set_num_threads(1);
    return 0;
}
