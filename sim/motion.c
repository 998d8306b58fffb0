/*
 * motion.c - closed-form tricycle motion on a constant-steering segment (see motion.h).
 */
#include "sim/motion.h"

#include <math.h>

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
    return s;
}

double sim_segment_omega(const sim_segment_t *seg)
{
    return seg->v * seg->kappa;
}

sim_pose_t sim_segment_pose(const sim_segment_t *seg, double t)
{
    double d = seg->v * (t - seg->t0); /* signed rear-axle travel */
    sim_pose_t p = seg->p0;
    double k = seg->kappa;
    double dth = k * d;
    if (fabs(dth) < 1e-9) {
        /* Straight (or nearly): second-order series of the arc, exact to rounding here. */
        double c = cos(p.th + 0.5 * dth), s = sin(p.th + 0.5 * dth);
        p.x += d * c;
        p.y += d * s;
    } else {
        p.x += (sin(p.th + dth) - sin(p.th)) / k;
        p.y -= (cos(p.th + dth) - cos(p.th)) / k;
    }
    p.th += dth;
    return p;
}

double sim_segment_front(const sim_segment_t *seg, double t)
{
    return seg->front0 + fabs(seg->v) * seg->front_per_rear * (t - seg->t0);
}

double sim_segment_time_at_front(const sim_segment_t *seg, double front, double after)
{
    double rate = fabs(seg->v) * seg->front_per_rear;
    if (rate <= 0.0)
        return INFINITY;
    double t = seg->t0 + (front - seg->front0) / rate;
    return t < after ? after : t;
}
