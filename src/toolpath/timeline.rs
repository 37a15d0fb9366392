//! The commanded motion in time (qiu §4-1): each segment of the program is
//! run at its programmed feed with a constant path speed, giving each axis
//! the commanded velocity `f_b(t)`. Besides the position `p(t)` the timeline
//! gives its running integral `Q(t) = ∫₀ᵗ (p − p₀) dτ` in closed form
//! (quadratic on lines, sine/cosine on arcs), because Eq. 1's moving
//! average of the velocity is, in position, `(Q(t) − Q(t − tA)) / tA`, and
//! the closed form makes it exact at any sampling interval.
//!
//! Before the first segment the tool stands at the start, after the last at
//! the end. Zero-length moves take no time. Only X, Y, Z are timed.
//!
//! Units: mm, s, mm/s.
//!
//! Memory: an item of a line holds no velocity (it is `(p1 − p0) / tau`,
//! computed where it is read, the same expression and so the same bits as
//! when it was stored) and an arc's constants are boxed, so a line's item
//! is 104 B in wasm32 instead of 184 B (a 2 M-line program: 160 MB less).

use crate::nc::program::{Motion, Segment};

/// One timed piece of the command.
#[derive(Debug, Clone)]
pub struct Item {
    /// Index of the segment in the program.
    pub segment: usize,
    /// Start time, s.
    pub t0: f64,
    /// Duration, s.
    pub tau: f64,
    /// Start point, mm.
    pub p0: [f64; 3],
    /// End point, mm.
    pub p1: [f64; 3],
    /// `Q` at `t0`, mm·s.
    pub q0: [f64; 3],
    geo: Geo,
}

#[derive(Debug, Clone)]
enum Geo {
    Still,
    /// At the constant velocity `(p1 − p0) / tau` ([`Item::line_velocity`]).
    Line,
    Arc(Box<ArcGeo>),
}

/// An arc run at the constant angular rate `w` from the angle `th0`
/// (whose `(sin, cos)` is `sc0`) about `c` of radius `r` in the plane of
/// `axes` `(u, v, normal)`, rising `vn` along the normal. mm, rad, s.
#[derive(Debug, Clone, Copy)]
struct ArcGeo {
    c: [f64; 3],
    r: f64,
    th0: f64,
    w: f64,
    axes: (usize, usize, usize),
    vn: f64,
    sc0: (f64, f64),
}

impl ArcGeo {
    /// Sine and cosine of the angle `u` seconds into the arc.
    #[inline]
    fn sin_cos_at(&self, u: f64) -> (f64, f64) {
        (self.th0 + self.w * u).sin_cos()
    }
}

/// The timed command of a whole program.
#[derive(Debug, Clone)]
pub struct Timeline {
    /// Items in time order (zero-length moves dropped).
    pub items: Vec<Item>,
    /// Start point, mm.
    pub origin: [f64; 3],
    /// End of the last item, s.
    pub end_time: f64,
    /// Highest path speed, mm/s.
    pub max_speed: f64,
}

impl Timeline {
    /// Times `segments` at their feeds × `feed_override`; rapids at
    /// `rapid_feed` (mm/min). Pass the rapid's settling time with
    /// [`Timeline::with_rapid_stop`].
    ///
    /// # Examples
    /// ```
    /// use mtmotion::{nc::program::parse, toolpath::timeline::Timeline};
    /// let p = parse("G1 X10 F600").unwrap(); // 10 mm/s
    /// let tl = Timeline::new(&p.segments, 20000.0, 1.0);
    /// assert!((tl.end_time - 1.0).abs() < 1e-12);
    /// let mut h = 0;
    /// assert!((tl.pos(0.25, &mut h)[0] - 2.5).abs() < 1e-12);
    /// assert!((tl.integral(1.0, &mut h)[0] - 5.0).abs() < 1e-12);
    /// ```
    pub fn new(segments: &[Segment], rapid_feed: f64, feed_override: f64) -> Self {
        Self::with_rapid_stop(segments, rapid_feed, feed_override, 0.0)
    }

    /// As [`Timeline::new`], with the tool standing still for
    /// `rapid_stop` seconds after every G0 (the NC's in-position check).
    pub fn with_rapid_stop(
        segments: &[Segment],
        rapid_feed: f64,
        feed_override: f64,
        rapid_stop: f64,
    ) -> Self {
        Self::with_stops(segments, rapid_feed, feed_override, rapid_stop, 0.0)
    }

    /// As [`Timeline::with_rapid_stop`], and every G4 dwell also waits
    /// `dwell_stop` seconds before its own time (the exact stop and
    /// in-position check a real NC makes before dwelling; qiu §4-3(2)).
    ///
    /// # Examples
    /// ```
    /// use mtmotion::{nc::program::parse, toolpath::timeline::Timeline};
    /// let p = parse("G1 X10 F600\nG4 P0.1\nG1 X20").unwrap();
    /// let plain = Timeline::new(&p.segments, 2e4, 1.0).end_time;
    /// let stop = Timeline::with_stops(&p.segments, 2e4, 1.0, 0.0, 0.05).end_time;
    /// assert!((plain - 2.1).abs() < 1e-12 && (stop - 2.15).abs() < 1e-12);
    /// ```
    pub fn with_stops(
        segments: &[Segment],
        rapid_feed: f64,
        feed_override: f64,
        rapid_stop: f64,
        dwell_stop: f64,
    ) -> Self {
        let origin = segments.first().map_or([0.0; 3], |s| s.start.p());
        // Room for every item at once: one per segment and one more per
        // rapid's stop (a push past the room doubles it, and while it is
        // copied both are held: 3 × 208 MB for a 2 M-line program in wasm).
        let stops = if rapid_stop > 0.0 {
            segments
                .iter()
                .filter(|s| matches!(s.motion, Motion::Rapid))
                .count()
        } else {
            0
        };
        let mut tl = Self {
            items: Vec::with_capacity(segments.len() + stops),
            origin,
            end_time: 0.0,
            max_speed: 0.0,
        };
        let mut q = [0.0; 3];
        for (i, s) in segments.iter().enumerate() {
            let Some((tau, geo, speed)) = timed(s, rapid_feed, feed_override, dwell_stop) else {
                continue;
            };
            tl.max_speed = tl.max_speed.max(speed);
            if tau <= 0.0 {
                continue;
            }
            let (p0, p1) = (s.start.p(), s.end.p());
            q = tl.push(i, tau, p0, p1, geo, q);
            if matches!(s.motion, Motion::Rapid) && rapid_stop > 0.0 {
                q = tl.push(i, rapid_stop, p1, p1, Geo::Still, q);
            }
        }
        tl
    }

    /// Appends an item of segment `segment` lasting `tau` s from `p0` to
    /// `p1` at the current end time, with `Q = q` at its start; returns `Q`
    /// at its end.
    fn push(
        &mut self,
        segment: usize,
        tau: f64,
        p0: [f64; 3],
        p1: [f64; 3],
        geo: Geo,
        q: [f64; 3],
    ) -> [f64; 3] {
        let item = Item {
            segment,
            t0: self.end_time,
            tau,
            p0,
            p1,
            q0: q,
            geo,
        };
        self.end_time += tau;
        let q1 = item.local_integral(tau, self.origin, q);
        self.items.push(item);
        q1
    }

    /// The item in force at `t`, starting the search at `hint` (updated).
    /// `None` before the first and after the last item.
    #[inline]
    pub fn locate(&self, t: f64, hint: &mut usize) -> Option<&Item> {
        let n = self.items.len();
        if n == 0 || t < 0.0 || t >= self.end_time {
            return None;
        }
        let mut i = (*hint).min(n - 1);
        while i > 0 && self.items[i].t0 > t {
            i -= 1;
        }
        while i + 1 < n && self.items[i + 1].t0 <= t {
            i += 1;
        }
        *hint = i;
        self.items.get(i)
    }

    /// Commanded position at `t`, mm.
    #[inline]
    pub fn pos(&self, t: f64, hint: &mut usize) -> [f64; 3] {
        match self.locate(t, hint) {
            Some(it) => it.pos(t - it.t0),
            None if t < 0.0 || self.items.is_empty() => self.origin,
            None => self.items.last().map_or(self.origin, |it| it.p1),
        }
    }

    /// Commanded velocity `f_b(t)`, mm/s.
    #[inline]
    pub fn vel(&self, t: f64, hint: &mut usize) -> [f64; 3] {
        self.locate(t, hint)
            .map_or([0.0; 3], |it| it.vel(t - it.t0))
    }

    /// Position, velocity and `Q` at `t` in one lookup.
    #[inline]
    pub fn eval(&self, t: f64, hint: &mut usize) -> ([f64; 3], [f64; 3], [f64; 3]) {
        match self.locate(t, hint) {
            Some(it) => it.eval(t - it.t0, self.origin),
            None => (self.pos(t, hint), [0.0; 3], self.integral(t, hint)),
        }
    }

    /// `Q(t) = ∫₀ᵗ (p − origin) dτ`, mm·s (zero for `t ≤ 0`).
    #[inline]
    pub fn integral(&self, t: f64, hint: &mut usize) -> [f64; 3] {
        if t <= 0.0 {
            return [0.0; 3];
        }
        match self.locate(t, hint) {
            Some(it) => it.local_integral(t - it.t0, self.origin, it.q0),
            None => match self.items.last() {
                Some(it) => {
                    let qe = it.local_integral(it.tau, self.origin, it.q0);
                    let dt = t - self.end_time;
                    let o = self.origin;
                    [
                        qe[0] + (it.p1[0] - o[0]) * dt,
                        qe[1] + (it.p1[1] - o[1]) * dt,
                        qe[2] + (it.p1[2] - o[2]) * dt,
                    ]
                }
                None => [0.0; 3],
            },
        }
    }
}

/// Duration (s), geometry and path speed (mm/s; 0 for a dwell) of segment
/// `s` at its feed × `feed_override`, a rapid at `rapid_feed` (mm/min), a
/// dwell waiting `dwell_stop` s before its own time. `None` for a move of no
/// length or no feed.
fn timed(
    s: &Segment,
    rapid_feed: f64,
    feed_override: f64,
    dwell_stop: f64,
) -> Option<(f64, Geo, f64)> {
    let m = match s.motion {
        Motion::Dwell { seconds } => return Some((seconds + dwell_stop, Geo::Still, 0.0)),
        m => m,
    };
    let len = s.length();
    let feed = match m {
        Motion::Rapid => rapid_feed,
        _ => s.feed * feed_override,
    } / 60.0;
    if len <= 0.0 || feed <= 0.0 {
        return None;
    }
    let tau = len / feed;
    Some((tau, Geo::moving(m, s.start.p(), s.end.p(), tau), feed))
}

impl Geo {
    /// The geometry of motion `m` from `p0` to `p1` run in `tau` s: an arc
    /// at constant angular rate, anything else a line at constant velocity.
    fn moving(m: Motion, p0: [f64; 3], p1: [f64; 3], tau: f64) -> Self {
        match m {
            Motion::Arc(a) => {
                let axes = a.plane.axes();
                let (u, v, n) = axes;
                Geo::Arc(Box::new(ArcGeo {
                    c: a.center,
                    r: a.radius,
                    th0: (p0[v] - a.center[v]).atan2(p0[u] - a.center[u]),
                    w: a.sweep / tau,
                    axes,
                    vn: (p1[n] - p0[n]) / tau,
                    sc0: (p0[v] - a.center[v]).atan2(p0[u] - a.center[u]).sin_cos(),
                }))
            }
            _ => Geo::Line,
        }
    }
}

impl Item {
    /// The velocity of a line item, mm/s: `(p1 − p0) / tau`.
    #[inline]
    fn line_velocity(&self) -> [f64; 3] {
        let (p0, p1, tau) = (self.p0, self.p1, self.tau);
        [
            (p1[0] - p0[0]) / tau,
            (p1[1] - p0[1]) / tau,
            (p1[2] - p0[2]) / tau,
        ]
    }

    /// Position `u` seconds into the item, mm.
    #[inline]
    pub fn pos(&self, u: f64) -> [f64; 3] {
        match self.geo {
            Geo::Still => self.p0,
            Geo::Line => {
                let v = self.line_velocity();
                [
                    self.p0[0] + v[0] * u,
                    self.p0[1] + v[1] * u,
                    self.p0[2] + v[2] * u,
                ]
            }
            Geo::Arc(ref g) => {
                let ((s, co), (a, b, n)) = (g.sin_cos_at(u), g.axes);
                let mut p = [0.0; 3];
                p[a] = g.c[a] + g.r * co;
                p[b] = g.c[b] + g.r * s;
                p[n] = self.p0[n] + g.vn * u;
                p
            }
        }
    }

    /// Velocity `u` seconds into the item, mm/s.
    #[inline]
    pub fn vel(&self, u: f64) -> [f64; 3] {
        match self.geo {
            Geo::Still => [0.0; 3],
            Geo::Line => self.line_velocity(),
            Geo::Arc(ref g) => {
                let ((s, co), (a, b, n), rw) = (g.sin_cos_at(u), g.axes, g.r * g.w);
                let mut v = [0.0; 3];
                v[a] = -rw * s;
                v[b] = rw * co;
                v[n] = g.vn;
                v
            }
        }
    }

    /// `∫₀ᵘ (p − p0) dτ`, the integral of the item's own displacement, mm·s.
    #[inline]
    pub fn displacement_integral(&self, u: f64) -> [f64; 3] {
        self.local_integral(u, self.p0, [0.0; 3])
    }

    /// Position, velocity and `q0 + ∫₀ᵘ (p − origin) dτ` at `u`, with one
    /// sine/cosine evaluation.
    #[inline]
    pub fn eval(&self, u: f64, o: [f64; 3]) -> ([f64; 3], [f64; 3], [f64; 3]) {
        match self.arc_phase() {
            Some((th0, w)) => self.eval_with(u, o, (th0 + w * u).sin_cos()),
            None => self.eval_with(u, o, (0.0, 1.0)),
        }
    }

    /// For an arc, its angle at the start and its angular rate `(θ₀, ω)`
    /// (rad, rad/s): the angle `u` seconds in is `θ₀ + ω·u`. `None` for
    /// lines and stops.
    #[inline]
    pub fn arc_phase(&self) -> Option<(f64, f64)> {
        match self.geo {
            Geo::Arc(ref g) => Some((g.th0, g.w)),
            _ => None,
        }
    }

    /// As [`Item::eval`], with the arc angle's `(sin, cos)` at `u` given by
    /// the caller (ignored for lines and stops), so a sampler can step them
    /// by a rotation instead of evaluating them afresh.
    #[inline]
    pub fn eval_with(
        &self,
        u: f64,
        o: [f64; 3],
        (s1, c1): (f64, f64),
    ) -> ([f64; 3], [f64; 3], [f64; 3]) {
        match self.geo {
            Geo::Arc(ref g) => {
                let ArcGeo {
                    c,
                    r,
                    w,
                    axes: (a, b, n),
                    vn,
                    sc0: (s0, c0),
                    ..
                } = **g;
                let mut p = [0.0; 3];
                let mut v = [0.0; 3];
                let mut q = self.q0;
                p[a] = c[a] + r * c1;
                p[b] = c[b] + r * s1;
                p[n] = self.p0[n] + vn * u;
                v[a] = -r * w * s1;
                v[b] = r * w * c1;
                v[n] = vn;
                let k = r / w;
                q[a] += (c[a] - o[a]) * u + k * (s1 - s0);
                q[b] += (c[b] - o[b]) * u - k * (c1 - c0);
                q[n] += (self.p0[n] - o[n]) * u + 0.5 * vn * u * u;
                (p, v, q)
            }
            // The same expressions as `pos`, `vel` and `local_integral`,
            // written out so the per-sample path has no further calls.
            Geo::Line => {
                let v = self.line_velocity();
                let (p0, q0) = (self.p0, self.q0);
                let h = 0.5 * u * u;
                let mut p = [0.0; 3];
                let mut q = [0.0; 3];
                for ax in 0..3 {
                    p[ax] = p0[ax] + v[ax] * u;
                    q[ax] = q0[ax] + (p0[ax] - o[ax]) * u + v[ax] * h;
                }
                (p, v, q)
            }
            Geo::Still => {
                let (p0, q0) = (self.p0, self.q0);
                let mut q = [0.0; 3];
                for ax in 0..3 {
                    q[ax] = q0[ax] + (p0[ax] - o[ax]) * u;
                }
                (p0, [0.0; 3], q)
            }
        }
    }

    /// `q0 + ∫₀ᵘ (p − origin) dτ`, mm·s.
    #[inline]
    fn local_integral(&self, u: f64, o: [f64; 3], q0: [f64; 3]) -> [f64; 3] {
        let d = [self.p0[0] - o[0], self.p0[1] - o[1], self.p0[2] - o[2]];
        match self.geo {
            Geo::Still => [q0[0] + d[0] * u, q0[1] + d[1] * u, q0[2] + d[2] * u],
            Geo::Line => {
                let v = self.line_velocity();
                let h = 0.5 * u * u;
                [
                    q0[0] + d[0] * u + v[0] * h,
                    q0[1] + d[1] * u + v[1] * h,
                    q0[2] + d[2] * u + v[2] * h,
                ]
            }
            Geo::Arc(ref g) => {
                let ArcGeo {
                    c,
                    r,
                    th0,
                    w,
                    axes: (a, b, n),
                    vn,
                    sc0,
                } = **g;
                let (s0, c0) = sc0;
                let (s1, c1) = (th0 + w * u).sin_cos();
                let mut q = q0;
                // ∫ r cos(th0 + w τ) dτ = r (sin θ1 − sin θ0) / w, written
                // without dividing by a tiny w for very short arcs.
                let k = r / w;
                q[a] += (c[a] - o[a]) * u + k * (s1 - s0);
                q[b] += (c[b] - o[b]) * u - k * (c1 - c0);
                q[n] += d[n] * u + 0.5 * vn * u * u;
                q
            }
        }
    }
}
