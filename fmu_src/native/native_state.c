/* The compiled FMU's serialised state: magic, format version, phase, the terminate flag, the
   GUID's CRC-32, the model's array sizes, the last good time, the arrays' doubles, and a CRC-32
   of all that, little-endian on every platform.  Read only after every byte is checked: the
   length this model's state has, the magic, the checksum, the version, this FMU's GUID, the
   sizes; nothing in it sizes an allocation. */
#include <stdint.h>
#include <string.h>

#include "native_model.h"
#include "native_state.h"

static const char MAGIC[8] = {'T', 'T', 'N', 'A', 'T', 'V', '0', '1'};
enum { HEADER = 8 + 4 * 4 + A_COUNT * 4 + 8 };   /* magic, version, phase, flag, GUID's CRC, sizes, time */

static uint32_t crc32(const unsigned char *p, size_t n)
{
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        crc ^= p[i];
        for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

static void put_u32(unsigned char *p, uint32_t x)
{
    for (int i = 0; i < 4; ++i) p[i] = (unsigned char)(x >> (8 * i));
}

static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void put_f64(unsigned char *p, double x)
{
    uint64_t u;
    memcpy(&u, &x, 8);
    for (int i = 0; i < 8; ++i) p[i] = (unsigned char)(u >> (8 * i));
}

static double get_f64(const unsigned char *p)
{
    uint64_t u = 0;
    for (int i = 0; i < 8; ++i) u |= (uint64_t)p[i] << (8 * i);
    double x;
    memcpy(&x, &u, 8);
    return x;
}

size_t native_state_size(size_t n_data) { return HEADER + 8 * n_data + 4; }

static uint32_t guid_crc(void)
{
    return crc32((const unsigned char *)MODEL_GUID, strlen(MODEL_GUID));
}

void native_state_write(unsigned char *p, uint32_t phase, uint32_t wants, double t,
                        const double *data, size_t n_data)
{
    memcpy(p, MAGIC, 8);
    put_u32(p + 8, 1);
    put_u32(p + 12, phase);
    put_u32(p + 16, wants);
    put_u32(p + 20, guid_crc());
    for (int a = 0; a < A_COUNT; ++a) put_u32(p + 24 + 4 * a, (uint32_t)MODEL_SIZES[a]);
    put_f64(p + 24 + 4 * A_COUNT, t);
    for (size_t i = 0; i < n_data; ++i) put_f64(p + HEADER + 8 * i, data[i]);
    put_u32(p + HEADER + 8 * n_data, crc32(p, HEADER + 8 * n_data));
}

const char *native_state_check(const unsigned char *p, size_t size, size_t n_data,
                               uint32_t max_phase)
{
    if (size != native_state_size(n_data) || memcmp(p, MAGIC, 8) != 0)
        return "not a serialised state of this FMU (bad magic or size)";
    if (crc32(p, size - 4) != get_u32(p + size - 4))
        return "the state is damaged (checksum mismatch)";
    if (get_u32(p + 8) != 1) return "corrupt state: another format version";
    if (get_u32(p + 20) != guid_crc()) return "state of another FMU or build (GUID)";
    if (get_u32(p + 12) > max_phase || get_u32(p + 16) > 1) return "corrupt state: its phase";
    for (int a = 0; a < A_COUNT; ++a)
        if (get_u32(p + 24 + 4 * a) != (uint32_t)MODEL_SIZES[a]) return "corrupt state: its sizes";
    return NULL;
}

void native_state_read(const unsigned char *p, uint32_t *phase, uint32_t *wants, double *t,
                       double *data, size_t n_data)
{
    *phase = get_u32(p + 12);
    *wants = get_u32(p + 16);
    *t = get_f64(p + 24 + 4 * A_COUNT);
    for (size_t i = 0; i < n_data; ++i) data[i] = get_f64(p + HEADER + 8 * i);
}
