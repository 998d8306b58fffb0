/*
 * motion.c - closed-form tricycle motion on a constant-steering segment (see motion.h).
 */
#include "sim/motion.h"

#include <math.h>
#include <stddef.h>

sim_segment_t sim_segment(double t, sim_pose_t p, double front_rolled, double alpha, double v,
                          double wheelbase)
{
    sim_segment_t s;
    s.t0 = t;
    s.p0 = p;
    s.kappa = tan(alpha) / wheelbase;
    s.v = v;
    s.front_per_rear = 1.0 / cos(alpha);
    s.front0 = front_rolled;
    s.decel = 0.0;
    return s;
}

double sim_segment_stop_time(const sim_segment_t *seg)
{
    return seg->decel > 0.0 ? seg->t0 + fabs(seg->v) / seg->decel : INFINITY;
}

double sim_segment_travel(const sim_segment_t *seg, double t)
{
    if (seg->decel <= 0.0)
        return seg->v * (t - seg->t0);
    double tau = fmin(t, sim_segment_stop_time(seg)) - seg->t0;
    double d = fabs(seg->v) * tau - 0.5 * seg->decel * tau * tau;
    return seg->v < 0.0 ? -d : d;
}

double sim_segment_speed(const sim_segment_t *seg, double t)
{
    if (seg->decel <= 0.0)
        return seg->v;
    double m = fabs(seg->v) - seg->decel * (t - seg->t0);
    if (m <= 0.0)
        return 0.0;
    return seg->v < 0.0 ? -m : m;
}

double sim_segment_time_at_travel(const sim_segment_t *seg, double dist)
{
    double v = fabs(seg->v);
    if (v <= 0.0)
        return INFINITY;
    if (seg->decel <= 0.0)
        return seg->t0 + dist / v;
    /* |v| tau - a tau^2 / 2 = dist, the smaller root, in the form that does not cancel */
    double disc = v * v - 2.0 * seg->decel * dist;
    if (disc < 0.0)
        return INFINITY; /* stops first */
    return seg->t0 + 2.0 * dist / (v + sqrt(disc));
}

double sim_segment_omega(const sim_segment_t *seg)
{
    return seg->v * seg->kappa;
}

/* The pose at @p t; with @p trig (cos, sin) of its heading too. */
static inline sim_pose_t pose_at(const sim_segment_t *seg, double t, double trig[2])
{
    double d = sim_segment_travel(seg, t); /* signed rear-axle travel */
    sim_pose_t p = seg->p0;
    double k = seg->kappa;
    double dth = k * d;
    if (fabs(dth) < 1e-9) {
        /* Straight (or nearly): second-order series of the arc, exact to rounding here. */
        double c = cos(p.th + 0.5 * dth), s = sin(p.th + 0.5 * dth);
        p.x += d * c;
        p.y += d * s;
        if (trig && dth == 0.0) { /* the heading's own */
            trig[0] = c;
            trig[1] = s;
            trig = NULL;
        }
    } else {
        double c = cos(p.th + dth), s = sin(p.th + dth);
        p.x += (s - sin(p.th)) / k;
        p.y -= (c - cos(p.th)) / k;
        if (trig) {
            trig[0] = c;
            trig[1] = s;
            trig = NULL;
        }
    }
    p.th += dth;
    if (trig) {
        trig[0] = cos(p.th);
        trig[1] = sin(p.th);
    }
    return p;
}

sim_pose_t sim_segment_pose(const sim_segment_t *seg, double t)
{
    return pose_at(seg, t, NULL);
}

sim_pose_t sim_segment_pose_trig(const sim_segment_t *seg, double t, double *cos_th, double *sin_th)
{
    double trig[2];
    sim_pose_t p = pose_at(seg, t, trig);
    *cos_th = trig[0];
    *sin_th = trig[1];
    return p;
}

double sim_segment_front(const sim_segment_t *seg, double t)
{
    if (seg->decel > 0.0)
        return seg->front0 + seg->front_per_rear * fabs(sim_segment_travel(seg, t));
    return seg->front0 + fabs(seg->v) * seg->front_per_rear * (t - seg->t0);
}

double sim_segment_time_at_front(const sim_segment_t *seg, double front, double after)
{
    double t;
    if (seg->decel > 0.0) {
        t = sim_segment_time_at_travel(seg, (front - seg->front0) / seg->front_per_rear);
    } else {
        double rate = fabs(seg->v) * seg->front_per_rear;
        if (rate <= 0.0)
            return INFINITY;
        t = seg->t0 + (front - seg->front0) / rate;
    }
    return t < after ? after : t;
}
