/* The compiled FMU's serialised state (native_state.c). */
#ifndef NATIVE_STATE_H
#define NATIVE_STATE_H

#include <stddef.h>
#include <stdint.h>

/* bytes of a state of n_data doubles */
size_t native_state_size(size_t n_data);
/* the state (phase, terminate flag, last good time t [s], the arrays) into p, native_state_size
   bytes */
void native_state_write(unsigned char *p, uint32_t phase, uint32_t wants, double t,
                        const double *data, size_t n_data);
/* NULL when the size bytes at p are a state of this FMU with n_data doubles (phase at most
   max_phase); else why not */
const char *native_state_check(const unsigned char *p, size_t size, size_t n_data,
                               uint32_t max_phase);
/* a checked state's values */
void native_state_read(const unsigned char *p, uint32_t *phase, uint32_t *wants, double *t,
                       double *data, size_t n_data);

#endif
