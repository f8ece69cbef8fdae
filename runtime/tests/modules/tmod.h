/* Parameter of the test module (port 0): a struct, to test setparam of structured values. */
#ifndef TMOD_H
#define TMOD_H
typedef struct { double x[3]; long flags; long run_ms; char label[256]; } TestParam;
#endif
