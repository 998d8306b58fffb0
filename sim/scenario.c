/*
 * scenario.c - scenario files: JSON (jansson) read through the tables generated from the
 * scenario's JSON Schema (see scenario.h, sim/schema.h), then what a schema cannot say.
 */
#include "sim/scenario.h"

#include <stdio.h>
#include <string.h>

#include "jsonval.h"
#include "sim/scenario_schema.h" /* generated: sim_scenario_schema */
#include "sim/schema.h"

const char *sim_scenario_mode_name(int mode)
{
    return mode >= 0 && mode < SIM_SCENARIO_MODE_COUNT ? node_mode_names[mode] : "?";
}

static int parse_root(json_t *root, const char *who, sim_scenario_t *sc, char *err, size_t errlen)
{
    memset(sc, 0, sizeof *sc);
    if (!json_is_object(root))
        return ac_fail(err, errlen, "a scenario must be a JSON object");
    if (sim_schema_read(&sim_scenario_schema, root, sc, "", who, err, errlen))
        return -1;
    /* A path point without a speed goes at the vehicle's. */
    for (size_t i = 0; i < sc->n_path; i++)
        if (sc->path[i].speed == 0.0)
            sc->path[i].speed = sc->speed;
    return 0;
}

int sim_scenario_parse(const char *text, sim_scenario_t *sc, char *err, size_t errlen)
{
    json_error_t jerr;
    json_t *root = json_loads(text, JSON_REJECT_DUPLICATES, &jerr);
    if (!root)
        return ac_fail(err, errlen, "line %d, column %d: %s", jerr.line, jerr.column, jerr.text);
    int rc = parse_root(root, "agv-sim", sc, err, errlen);
    json_decref(root);
    return rc;
}

int sim_scenario_load(const char *path, sim_scenario_t *sc, char *err, size_t errlen)
{
    json_error_t jerr;
    json_t *root = json_load_file(path, JSON_REJECT_DUPLICATES, &jerr);
    if (!root && jerr.line < 0)
        return ac_fail(err, errlen, "%s", jerr.text); /* cannot open or read the file */
    if (!root)
        return ac_fail(err, errlen, "%s: line %d, column %d: %s", path, jerr.line, jerr.column,
                       jerr.text);
    char inner[512], who[300];
    snprintf(who, sizeof who, "agv-sim: %s", path);
    int rc = parse_root(root, who, sc, inner, sizeof inner);
    json_decref(root);
    if (rc)
        return ac_fail(err, errlen, "%s: %s", path, inner);
    return 0;
}
