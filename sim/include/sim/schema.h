/*
 * schema.h - JSON input read into a C struct as a table says: the table is generated from a
 * JSON Schema (tools/gen_schema_c.py), so the keys, types, ranges and defaults the reader
 * checks are the schema's. Each node is one key: an object (its members), an array of objects
 * (its item), or a value stored in a field of the struct being filled (a double, an unsigned
 * integer of 32 or 64 bits, a bool, a character array, or an enum index as an int).
 * Errors name the key with its full path ("sensors.gyro.step_deg", "beacons[2].y") and the
 * value.
 */
#ifndef SIM_SCHEMA_H
#define SIM_SCHEMA_H

#include <jansson.h>
#include <stdbool.h>
#include <stddef.h>

typedef enum {
    SIM_SCHEMA_OBJECT,  /* members; stored through them */
    SIM_SCHEMA_ARRAY,   /* of objects: elements at offset + i * elem_size, count at count_offset */
    SIM_SCHEMA_NUMBER,  /* double = value * scale */
    SIM_SCHEMA_INTEGER, /* uint32_t or uint64_t (size), a number with no fraction */
    SIM_SCHEMA_BOOLEAN, /* bool */
    SIM_SCHEMA_STRING,  /* char[size], at most max characters */
    SIM_SCHEMA_ENUM     /* int: the index of the string in names */
} sim_schema_kind_t;

typedef struct sim_schema_node {
    const char *key;
    sim_schema_kind_t kind;
    bool required;
    bool has_default;
    bool closed;     /* object: keys beyond the members are warned about and ignored */
    double dflt;     /* number, integer, boolean (0/1), enum (index) */
    double min, max; /* number, integer: inclusive range; array: entries; string: length */
    double scale;    /* number: stored value per unit of the input */
    size_t offset;   /* value, array: the field within the struct being filled */
    size_t size;     /* value: the field's size */
    size_t count_offset, elem_size;        /* array: element count field (size_t), stride */
    const struct sim_schema_node *members; /* object: members; array: its item (an object) */
    size_t n_members;
    const char *const *names; /* enum */
    size_t n_names;
} sim_schema_node_t;

/**
 * Read @p v as @p node describes into the struct at @p base (an object node's members, an
 * array's elements and every value land at their offsets from @p base). @p path is the
 * key's full name ("" for the root). Absent members get their defaults (the members of an
 * absent object too); absent required ones are an error. Unknown members of a closed object
 * are warned about on stderr, prefixed with @p who. Returns 0, or -1 with the reason in
 * @p err (the struct then partly filled).
 */
int sim_schema_read(const sim_schema_node_t *node, json_t *v, void *base, const char *path,
                    const char *who, char *err, size_t errlen);

#endif
