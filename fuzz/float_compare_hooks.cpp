/// @file
/// GCC's -fsanitize-coverage=trace-cmp also reports floating-point comparisons, through two
/// hooks that libFuzzer does not define (clang never emits them). The FuzzBounded targets
/// ignore those comparisons: their inputs' structure is in the integer and byte ones.

extern "C" {

void __sanitizer_cov_trace_cmpf(float, float) {}
void __sanitizer_cov_trace_cmpd(double, double) {}
}
