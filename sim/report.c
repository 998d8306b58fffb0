/*
 * report.c - statistics and the JSON report (see report.h).
 */
#include "sim/report.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sim_stat_add(sim_stat_t *s, double x)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 256;
        double *v = realloc(s->v, cap * sizeof *v);
        if (!v) {
            fprintf(stderr, "agv-sim: out of memory\n");
            exit(3);
        }
        s->v = v;
        s->cap = cap;
    }
    s->v[s->n++] = x;
    s->sum += x;
    s->sumsq += x * x;
    if (s->n == 1 || x > s->max)
        s->max = x;
}

double sim_stat_mean(const sim_stat_t *s)
{
    return s->n ? s->sum / (double)s->n : 0.0;
}

double sim_stat_rms(const sim_stat_t *s)
{
    return s->n ? sqrt(s->sumsq / (double)s->n) : 0.0;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double sim_stat_quantile(sim_stat_t *s, double p)
{
    if (!s->n)
        return 0.0;
    qsort(s->v, s->n, sizeof s->v[0], cmp);
    size_t k = (size_t)ceil(p * (double)s->n);
    if (k < 1)
        k = 1;
    return s->v[k - 1];
}

void sim_stat_free(sim_stat_t *s)
{
    free(s->v);
    s->v = NULL;
    s->n = s->cap = 0;
}

/* A criterion missed: count it and append its text to the list. */
typedef struct {
    char *why;
    size_t whylen, len;
    int misses;
} misses_t;

static void miss(misses_t *m, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void miss(misses_t *m, const char *fmt, ...)
{
    m->misses++;
    if (m->len >= m->whylen)
        return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(m->why + m->len, m->whylen - m->len, fmt, ap);
    va_end(ap);
    m->len += n > 0 ? (size_t)n : 0;
}

int sim_report_judge(sim_report_t *r, const sim_success_t *c, char *why, size_t whylen)
{
    misses_t m = {why, whylen, 0, 0};
    if (whylen)
        why[0] = '\0';
    if (c->require_goal && !r->reached_goal)
        miss(&m, " goal not reached (stopped: %s);", r->stop_reason ? r->stop_reason : "?");
    if (c->stop_reason[0] &&
        (r->reached_goal || !r->stop_reason || strcmp(r->stop_reason, c->stop_reason) != 0))
        miss(&m, " stop reason %s, expected %s;", r->reached_goal ? "none (goal)" : r->stop_reason,
             c->stop_reason);
    if (sim_stat_mean(&r->cross_track) > c->max_cross_track_mean)
        miss(&m, " cross-track mean %.4f m > %.4f;", sim_stat_mean(&r->cross_track),
             c->max_cross_track_mean);
    if (r->cross_track.n && r->cross_track.max > c->max_cross_track_max)
        miss(&m, " cross-track max %.4f m > %.4f;", r->cross_track.max, c->max_cross_track_max);
    if (r->final_error > c->max_final_error)
        miss(&m, " final error %.4f m > %.4f;", r->final_error, c->max_final_error);
    if (r->fix_error.n && r->fix_error.max > c->max_fix_error)
        miss(&m, " fix error max %.4f m > %.4f;", r->fix_error.max, c->max_fix_error);
    double ratio = r->fixes_attempted ? (double)r->fixes_accepted / r->fixes_attempted : 0.0;
    if (ratio < c->min_fix_ratio)
        miss(&m, " %.0f%% of fixes accepted < %.0f%%;", 100 * ratio, 100 * c->min_fix_ratio);
    return m.misses == 0;
}

void sim_report_free(sim_report_t *r)
{
    sim_stat_free(&r->fix_error);
    sim_stat_free(&r->heading_error);
    sim_stat_free(&r->cross_track);
    sim_stat_free(&r->pursuit.true_error);
}

/* Fixed decimals: the text of a number never depends on float formatting quirks. */
static json_t *num(double v, int decimals)
{
    double scale = pow(10.0, decimals);
    double r = round(v * scale) / scale;
    if (r == 0.0 || !isfinite(r))
        r = isfinite(r) ? 0.0 : -1.0;
    return json_real(r);
}

static json_t *board_json(const sim_link_board_t *b)
{
    json_t *o = json_object();
    json_object_set_new(o, "tx_frames", json_integer(b->tx_frames));
    json_object_set_new(o, "rx_frames", json_integer(b->rx_frames));
    json_object_set_new(o, "tx_errors", json_integer(b->tx_errors));
    json_object_set_new(o, "rx_errors", json_integer(b->rx_errors));
    json_object_set_new(o, "rx_overruns", json_integer(b->rx_overruns));
    json_object_set_new(o, "tx_aborted", json_integer(b->tx_aborted));
    json_object_set_new(o, "error_passive", json_integer(b->error_passive));
    json_object_set_new(o, "bus_off", json_integer(b->bus_off));
    json_object_set_new(o, "recoveries", json_integer(b->recoveries));
    json_object_set_new(o, "heartbeats_sent", json_integer(b->heartbeats_sent));
    json_object_set_new(o, "heartbeats_missed", json_integer(b->heartbeats_missed));
    json_object_set_new(o, "silences", json_integer(b->silences));
    json_object_set_new(o, "send_refused", json_integer(b->send_refused));
    json_object_set_new(o, "message_errors", json_integer(b->message_errors));
    return o;
}

static json_t *link_json(const sim_link_report_t *l)
{
    json_t *o = json_object();
    json_object_set_new(o, "bus", json_string("can"));
    json_object_set_new(o, "bitrate_bps", json_integer(l->bitrate_bps));
    json_object_set_new(o, "frames", json_integer((json_int_t)l->frames));
    json_object_set_new(o, "bus_load", num(l->bus_load, 6));
    json_object_set_new(o, "errors", json_integer((json_int_t)l->errors));
    json_object_set_new(o, "lost", json_integer((json_int_t)l->lost));
    json_object_set_new(o, "bus_off", json_integer(l->bus_off));
    json_object_set_new(o, "recoveries", json_integer(l->recoveries));
    json_object_set_new(o, "recovery_ms_max", num(l->recovery_ms_max, 3));
    json_t *lat = json_object();
    for (size_t i = 0; i < l->n_latency; i++)
        json_object_set_new(lat, l->latency_name[i], num(l->latency_ms[i], 3));
    json_object_set_new(o, "latency_ms", lat);
    json_t *boards = json_object();
    json_object_set_new(boards, "main", board_json(&l->board[0]));
    json_object_set_new(boards, "nav", board_json(&l->board[1]));
    json_object_set_new(o, "boards", boards);
    return o;
}

static json_t *mean_max(double mean, double max)
{
    json_t *o = json_object();
    json_object_set_new(o, "mean", num(mean, 6));
    json_object_set_new(o, "max", num(max, 6));
    return o;
}

/* Set the counts @p v, named @p names, in @p o; returns @p o. */
static json_t *counts(json_t *o, const char *const *names, const uint32_t *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        json_object_set_new(o, names[i], json_integer(v[i]));
    return o;
}

static json_t *pursuit_json(sim_pursuit_report_t *p)
{
    json_t *o = json_object();
    json_object_set_new(o, "updates", json_integer(p->updates));
    json_object_set_new(o, "path_error_m", mean_max(p->error_mean, p->error_max));
    json_object_set_new(
        o, "true_path_error_m",
        mean_max(sim_stat_mean(&p->true_error), p->true_error.n ? p->true_error.max : 0.0));
    json_object_set_new(o, "speed_mps", num(p->moving > 0 ? p->distance / p->moving : 0.0, 4));
    json_t *rx = json_array();
    for (uint32_t k = 0; k < p->n_receivers && k < 2; k++) {
        static const char *const names[] = {"framed",      "resyncs", "skipped_bytes",
                                            "error_bytes", "dropped", "overruns"};
        static const char *const reasons[] = {"accepted", "zero", "jump", "too_close", "pair"};
        const uint32_t v[] = {p->rx[k].framed,      p->rx[k].resyncs, p->rx[k].skipped,
                              p->rx[k].error_bytes, p->rx[k].dropped, p->rx[k].overruns};
        json_t *one = counts(json_object(), reasons, p->rx[k].reason, 5);
        json_array_append_new(rx, counts(one, names, v, 6));
    }
    json_object_set_new(o, "receivers", rx);
    static const char *const src[] = {"updates",       "sent",         "outage", "dropouts",
                                      "no_sight",      "line_busy",    "zeros",  "wilds",
                                      "garbage_bytes", "corrupt_bytes"};
    json_object_set_new(o, "source", counts(json_object(), src, p->src, 10));
    static const char *const law[] = {"corrections",  "goal_switches", "slowdowns",
                                      "stops",        "resumes",       "regulations",
                                      "pair_rejects", "unpaired",      "nav_timeouts"};
    const uint32_t lv[] = {p->corrections,  p->goals,    p->slowdowns,
                           p->stops,        p->resumes,  p->regulations,
                           p->pair_rejects, p->unpaired, p->nav_timeouts};
    return counts(o, law, lv, 9);
}

char *sim_report_json(sim_report_t *r)
{
    json_t *root = json_object();
    json_object_set_new(root, "scenario", json_string(r->scenario));
    json_object_set_new(root, "seed", json_integer((json_int_t)r->seed));
    json_object_set_new(root, "mode", json_string(r->mode));
    json_object_set_new(root, "sim_time_s", num(r->sim_time, 6));
    json_object_set_new(root, "wall_time_s", num(r->wall_time, 6));
    json_object_set_new(root, "outcome", json_string(r->reached_goal ? "goal" : "stopped"));
    if (!r->reached_goal)
        json_object_set_new(root, "stop_reason",
                            json_string(r->stop_reason ? r->stop_reason : "unknown"));

    json_t *fixes = json_object();
    json_object_set_new(fixes, "attempted", json_integer(r->fixes_attempted));
    json_object_set_new(fixes, "accepted", json_integer(r->fixes_accepted));
    json_object_set_new(fixes, "rejected", json_integer(r->fixes_rejected));
    json_t *err = json_object();
    json_object_set_new(err, "rms", num(sim_stat_rms(&r->fix_error), 6));
    json_object_set_new(err, "p95", num(sim_stat_quantile(&r->fix_error, 0.95), 6));
    json_object_set_new(err, "max", num(r->fix_error.n ? r->fix_error.max : 0.0, 6));
    json_object_set_new(fixes, "error_m", err);
    json_t *herr = json_object();
    json_object_set_new(herr, "rms", num(sim_stat_rms(&r->heading_error), 5));
    json_object_set_new(herr, "max", num(r->heading_error.n ? r->heading_error.max : 0.0, 5));
    json_object_set_new(fixes, "heading_error_deg", herr);
    json_object_set_new(root, "fixes", fixes);

    json_t *path = json_object();
    json_object_set_new(path, "reached_goal", json_boolean(r->reached_goal));
    json_t *ct = json_object();
    json_object_set_new(ct, "mean", num(sim_stat_mean(&r->cross_track), 6));
    json_object_set_new(ct, "max", num(r->cross_track.n ? r->cross_track.max : 0.0, 6));
    json_object_set_new(path, "cross_track_m", ct);
    json_object_set_new(path, "final_error_m", num(r->final_error, 6));
    json_object_set_new(root, "path", path);

    json_object_set_new(root, "outcome", json_string(r->reached_goal ? "goal" : "stopped"));
    if (!r->reached_goal) {
        json_object_set_new(root, "stop_reason", json_string(r->stop_reason));
        json_object_set_new(root, "stop_at_s", num(r->stop_at, 6));
        if (r->standstill_at >= 0)
            json_object_set_new(root, "standstill_at_s", num(r->standstill_at, 6));
    }

    if (r->pursuit.on)
        json_object_set_new(root, "pursuit", pursuit_json(&r->pursuit));

    json_t *isr = json_object();
    for (size_t i = 0; i < r->n_isr; i++)
        json_object_set_new(isr, r->isr_name[i], json_integer((json_int_t)r->isr_count[i]));
    json_object_set_new(root, "isr", isr);
    json_object_set_new(root, "link", link_json(&r->link));

    char *s = json_dumps(root, JSON_INDENT(1) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(12));
    json_decref(root);
    return s;
}

int sim_report_write(sim_report_t *r, const char *path)
{
    char *s = sim_report_json(r);
    if (!s)
        return -1;
    FILE *f = fopen(path, "w");
    if (!f) {
        free(s);
        return -1;
    }
    int rc = fputs(s, f) < 0 || fputc('\n', f) < 0 ? -1 : 0;
    if (fclose(f))
        rc = -1;
    free(s);
    return rc;
}
