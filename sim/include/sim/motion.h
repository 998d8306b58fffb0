/*
 * motion.h - the truth trajectory of a tricycle vehicle: a steered front wheel a wheelbase L
 * ahead of the rear axle, reference point the rear-axle centre. Between drive commands the
 * steering angle is constant and the speed constant, or falling at a constant deceleration
 * until the vehicle stands (braking), so the rear axle follows a circle (or a line) exactly;
 * the simulator keeps one such segment at a time and evaluates it in closed form.
 *
 * Conventions: metres, seconds, radians, counter-clockwise; steering angle alpha left
 * positive; rear-axle curvature kappa = tan(alpha) / L; speed v of the rear axle, negative in
 * reverse; the front wheel rolls |v| / cos(alpha).
 */
#ifndef SIM_MOTION_H
#define SIM_MOTION_H

#include <stdbool.h>

typedef struct {
    double x, y, th; /* rear-axle centre, heading (rad, unwrapped) */
} sim_pose_t;

typedef struct {
    double t0;             /* start time, s */
    sim_pose_t p0;         /* pose at t0 */
    double kappa;          /* rear-axle curvature, 1/m, left positive */
    double v;              /* rear-axle speed, m/s (negative: reverse) */
    double front_per_rear; /* front-wheel travel per metre of rear travel, 1/cos(alpha) */
    double front0;         /* front-wheel distance rolled before t0, m (always increasing) */
    double decel;          /* m/s^2, >= 0: |v| falls at this rate until the vehicle stands */
} sim_segment_t;

/** A segment from pose @p p at time @p t with steering @p alpha (rad) and constant speed @p v. */
sim_segment_t sim_segment(double t, sim_pose_t p, double front_rolled, double alpha, double v,
                          double wheelbase);

/** Pose on the segment at time @p t (t >= seg->t0). */
sim_pose_t sim_segment_pose(const sim_segment_t *seg, double t);

/** sim_segment_pose() and the cosine and sine of its heading (the same numbers as cos() and
 * sin() of it: most often left over from the pose's own arithmetic). */
sim_pose_t sim_segment_pose_trig(const sim_segment_t *seg, double t, double *cos_th,
                                 double *sin_th);

/** Front-wheel distance rolled (total since the start of the run) at time @p t. */
double sim_segment_front(const sim_segment_t *seg, double t);

/**
 * Earliest time >= @p after at which the front-wheel total reaches @p front; INFINITY when the
 * vehicle stands.
 */
double sim_segment_time_at_front(const sim_segment_t *seg, double front, double after);

/** Heading rate at the segment's start, rad/s (constant unless the segment brakes). */
double sim_segment_omega(const sim_segment_t *seg);

/** Signed rear-axle travel from the segment's start to time @p t (t >= seg->t0), m. */
double sim_segment_travel(const sim_segment_t *seg, double t);

/** Rear-axle speed at time @p t (t >= seg->t0), m/s (negative in reverse; 0 once stopped). */
double sim_segment_speed(const sim_segment_t *seg, double t);

/** When a braking segment comes to a stand, s; INFINITY for a segment without braking. */
double sim_segment_stop_time(const sim_segment_t *seg);

/**
 * Earliest time at which the rear axle has travelled @p dist (m, >= 0, unsigned) since the
 * segment's start; INFINITY when it stands or stops first.
 */
double sim_segment_time_at_travel(const sim_segment_t *seg, double dist);

#endif
