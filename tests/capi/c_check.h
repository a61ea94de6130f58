/* The C tests' CHECK: reports a failed condition with the C API's last error message and
 * counts it in `failures` (each test's main returns failures ? 1 : 0). Include once per
 * test program, after <drape/drape.h> and <stdio.h>. */
#ifndef DRAPE_TESTS_CAPI_C_CHECK_H
#define DRAPE_TESTS_CAPI_C_CHECK_H

static int failures = 0;

#define CHECK(cond)                                                                              \
    do {                                                                                         \
        if (!(cond)) {                                                                           \
            fprintf(stderr, "%s:%d: CHECK failed: %s (last error: %s)\n", __FILE__, __LINE__, \
                    #cond, drape_last_error_message());                                          \
            ++failures;                                                                          \
        }                                                                                        \
    } while (0)

#endif
