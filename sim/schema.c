/*
 * schema.c - JSON input read into a C struct as a generated table says (see schema.h).
 */
#include "sim/schema.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jsonval.h"

/* A short rendering of a JSON value for error messages. */
static void show(json_t *v, char *buf, size_t n)
{
    char *s = json_dumps(v, JSON_ENCODE_ANY | JSON_COMPACT);
    snprintf(buf, n, "%s", s ? s : "?");
    if (s && strlen(s) >= n && n > 4)
        memcpy(buf + n - 4, "...", 4);
    free(s);
}

static void join(char *out, size_t n, const char *path, const char *key)
{
    snprintf(out, n, "%s%s%s", path, *path && *key ? "." : "", key);
}

static void store_default(const sim_schema_node_t *nd, char *base)
{
    void *f = base + nd->offset;
    switch (nd->kind) {
    case SIM_SCHEMA_NUMBER:
        *(double *)f = nd->dflt * nd->scale;
        break;
    case SIM_SCHEMA_INTEGER:
        if (nd->size == sizeof(uint64_t))
            *(uint64_t *)f = (uint64_t)nd->dflt;
        else
            *(uint32_t *)f = (uint32_t)nd->dflt;
        break;
    case SIM_SCHEMA_BOOLEAN:
        *(bool *)f = nd->dflt != 0;
        break;
    case SIM_SCHEMA_ENUM:
        *(int *)f = (int)nd->dflt;
        break;
    default:
        break;
    }
}

/* An absent object: its members' defaults, recursively. */
static void defaults(const sim_schema_node_t *nd, char *base)
{
    for (size_t i = 0; i < nd->n_members; i++) {
        const sim_schema_node_t *m = &nd->members[i];
        if (m->kind == SIM_SCHEMA_OBJECT)
            defaults(m, base);
        else if (m->has_default)
            store_default(m, base);
    }
}

static int read_value(const sim_schema_node_t *nd, json_t *v, char *base, const char *full,
                      const char *who, char *err, size_t errlen);

static int read_object(const sim_schema_node_t *nd, json_t *v, char *base, const char *full,
                       const char *who, char *err, size_t errlen)
{
    if (!json_is_object(v))
        return ac_fail(err, errlen, "%s: expected an object", *full ? full : "the file");
    if (nd->closed) {
        const char *k;
        json_t *x;
        json_object_foreach(v, k, x)
        {
            size_t i = 0;
            while (i < nd->n_members && strcmp(nd->members[i].key, k) != 0)
                i++;
            if (i == nd->n_members) {
                char name[160];
                join(name, sizeof name, full, k);
                fprintf(stderr, "%s: warning: unknown key \"%s\" ignored\n", who, name);
            }
        }
    }
    for (size_t i = 0; i < nd->n_members; i++) {
        const sim_schema_node_t *m = &nd->members[i];
        char name[160];
        join(name, sizeof name, full, m->key);
        json_t *x = json_object_get(v, m->key);
        if (!x) {
            if (m->required)
                return ac_fail(err, errlen, "missing \"%s\"", name);
            if (m->kind == SIM_SCHEMA_OBJECT)
                defaults(m, base);
            else if (m->has_default)
                store_default(m, base);
            continue;
        }
        if (read_value(m, x, base, name, who, err, errlen))
            return -1;
    }
    return 0;
}

static int read_array(const sim_schema_node_t *nd, json_t *v, char *base, const char *full,
                      const char *who, char *err, size_t errlen)
{
    if (!json_is_array(v))
        return ac_fail(err, errlen, "%s: expected an array", full);
    size_t n = json_array_size(v);
    if ((double)n < nd->min || (double)n > nd->max)
        return ac_fail(err, errlen, "%s: %zu entries, expected %.0f to %.0f", full, n, nd->min,
                       nd->max);
    for (size_t i = 0; i < n; i++) {
        char name[160];
        snprintf(name, sizeof name, "%s[%zu]", full, i);
        char *elem = base + nd->offset + i * nd->elem_size;
        if (read_object(nd->members, json_array_get(v, i), elem, name, who, err, errlen))
            return -1;
    }
    *(size_t *)(base + nd->count_offset) = n;
    return 0;
}

static int read_value(const sim_schema_node_t *nd, json_t *v, char *base, const char *full,
                      const char *who, char *err, size_t errlen)
{
    char shown[48];
    void *f = base + nd->offset;
    double d;
    switch (nd->kind) {
    case SIM_SCHEMA_OBJECT:
        return read_object(nd, v, base, full, who, err, errlen);
    case SIM_SCHEMA_ARRAY:
        return read_array(nd, v, base, full, who, err, errlen);
    case SIM_SCHEMA_NUMBER:
        if (ac_number_value(v, full, nd->min, nd->max, &d, err, errlen))
            return -1;
        *(double *)f = d * nd->scale;
        return 0;
    case SIM_SCHEMA_INTEGER:
        if (ac_number_value(v, full, nd->min, nd->max, &d, err, errlen))
            return -1;
        if (d != floor(d))
            return ac_fail(err, errlen, "%s: %.17g is not an integer", full, d);
        if (nd->size == sizeof(uint64_t))
            *(uint64_t *)f = (uint64_t)d;
        else
            *(uint32_t *)f = (uint32_t)d;
        return 0;
    case SIM_SCHEMA_BOOLEAN:
        if (!json_is_boolean(v)) {
            show(v, shown, sizeof shown);
            return ac_fail(err, errlen, "%s: expected true or false, got %s", full, shown);
        }
        *(bool *)f = json_is_true(v);
        return 0;
    case SIM_SCHEMA_STRING: {
        const char *s = json_string_value(v);
        if (!s) {
            show(v, shown, sizeof shown);
            return ac_fail(err, errlen, "%s: expected a string, got %s", full, shown);
        }
        if ((double)strlen(s) > nd->max)
            return ac_fail(err, errlen, "%s: \"%.40s...\" is longer than %.0f characters", full, s,
                           nd->max);
        snprintf(f, nd->size, "%s", s);
        return 0;
    }
    case SIM_SCHEMA_ENUM: {
        char list[160] = "";
        size_t len = 0;
        for (size_t i = 0; i < nd->n_names && len < sizeof list; i++)
            len += (size_t)snprintf(list + len, sizeof list - len, "%s\"%s\"", i ? ", " : "",
                                    nd->names[i]);
        const char *s = json_string_value(v);
        if (!s) {
            show(v, shown, sizeof shown);
            return ac_fail(err, errlen, "%s: expected one of %s, got %s", full, list, shown);
        }
        for (size_t i = 0; i < nd->n_names; i++)
            if (strcmp(s, nd->names[i]) == 0) {
                *(int *)f = (int)i;
                return 0;
            }
        return ac_fail(err, errlen, "%s: \"%s\" is not one of %s", full, s, list);
    }
    }
    return ac_fail(err, errlen, "%s: unknown node kind %d", full, (int)nd->kind);
}

int sim_schema_read(const sim_schema_node_t *node, json_t *v, void *base, const char *path,
                    const char *who, char *err, size_t errlen)
{
    return read_value(node, v, base, path, who, err, errlen);
}
