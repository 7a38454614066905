use super::*;

/// Odd, even and non-square grids around the origin (m).
fn grids() -> Vec<Grid> {
    vec![
        Grid::new(17, 9, -1.0e-3, 1.1e-3, -0.6e-3, 0.5e-3),
        Grid::new(16, 24, -0.9e-3, 0.8e-3, -1.0e-3, 1.2e-3),
        Grid::new(33, 31, -1.3e-3, 1.0e-3, -1.1e-3, 1.05e-3),
        Grid::new(40, 7, -1.0e-3, 1.0e-3, -0.7e-3, 0.9e-3),
    ]
}

fn sample(s: &Surface, g: &Grid, shift: f64) -> Vec<f64> {
    let mut out = vec![f64::NAN; g.len()]; // cell_averages must overwrite
    s.cell_averages(g, shift, &mut out);
    out
}

fn one(shape: FeatureShape, centre: (f64, f64)) -> Surface {
    Surface::new(vec![Feature::new(shape, centre)])
}

fn volume(out: &[f64], g: &Grid) -> f64 {
    out.iter().sum::<f64>() * g.cell_area()
}

fn pit(width: f64, length: f64, depth: f64) -> FeatureShape {
    FeatureShape::Pit {
        width,
        length,
        depth,
    }
}

fn dent(width: f64, length: f64, depth: f64) -> FeatureShape {
    FeatureShape::Dent {
        width,
        length,
        depth,
    }
}

const D: f64 = 2.5e-8;

#[test]
fn gauss_legendre_rule_is_exact_to_degree_11() {
    let w: f64 = GL6.iter().map(|p| p.1).sum();
    assert!((w - 2.0).abs() < 1e-15, "weights sum {w}");
    for k in 0..=12 {
        let q: f64 = GL6.iter().map(|&(t, w)| w * t.powi(k)).sum();
        let exact = if k % 2 == 1 {
            0.0
        } else {
            2.0 / (k + 1) as f64
        };
        if k <= 11 {
            assert!((q - exact).abs() < 1e-15, "x^{k}: {q} vs {exact}");
        } else {
            assert!((q - exact).abs() > 1e-6, "x^12 should not be exact");
        }
    }
}

#[test]
fn gauss_legendre_4_is_exact_to_degree_7() {
    for k in 0..=8 {
        let q: f64 = GL4.iter().map(|&(t, w)| w * t.powi(k)).sum();
        let exact = if k % 2 == 1 {
            0.0
        } else {
            2.0 / (k + 1) as f64
        };
        if k <= 7 {
            assert!((q - exact).abs() < 1e-15, "x^{k}: {q} vs {exact}");
        } else {
            assert!((q - exact).abs() > 1e-4, "x^8 should not be exact");
        }
    }
}

#[test]
fn pit_cell_averages_integrate_to_its_volume() {
    for g in grids() {
        for &(c, shift) in &[((0.0, 0.0), 0.0), ((0.123e-3, -0.071e-3), 0.0371e-3)] {
            let (w, l) = (0.31e-3, 0.47e-3);
            let out = sample(&one(pit(w, l, D), c), &g, shift);
            let v = volume(&out, &g);
            assert!(
                (v / (D * w * l) - 1.0).abs() < 1e-13,
                "{g:?}: {v} vs {}",
                D * w * l
            );
            assert!(out.iter().all(|&o| (0.0..=D).contains(&o)));
        }
    }
}

#[test]
fn pattern_volume_is_rows_times_columns_times_one() {
    for g in grids() {
        let (w, l) = (0.1e-3, 0.15e-3);
        let p = Pattern {
            rows: 3,
            columns: 3,
            row_pitch: 0.25e-3,
            column_pitch: 0.3e-3,
        };
        for shape in [pit(w, l, D), dent(w, l, D)] {
            let single = shape.volume().unwrap();
            let f = Feature::new(shape, (0.02e-3, 0.01e-3)).with_pattern(p);
            assert_eq!(f.volume(), Some(9.0 * single));
            let s = Surface::new(vec![f.clone()]);
            let out = sample(&s, &g, 0.011e-3);
            assert!((volume(&out, &g) / (9.0 * single) - 1.0).abs() < 1e-12);
            // the same as nine features placed by hand
            let mut by_hand = Vec::new();
            for (ox, oy) in p.offsets() {
                by_hand.push(Feature::new(f.shape.clone(), (0.02e-3 + ox, 0.01e-3 + oy)));
            }
            let hand = sample(&Surface::new(by_hand), &g, 0.011e-3);
            for (a, b) in out.iter().zip(&hand) {
                assert!((a - b).abs() <= 1e-15 * D);
            }
        }
    }
}

#[test]
fn pattern_offsets_are_centred_and_ordered() {
    let p = Pattern {
        rows: 3,
        columns: 2,
        row_pitch: 1.0,
        column_pitch: 4.0,
    };
    let o: Vec<_> = p.offsets().collect();
    assert_eq!(
        o,
        vec![
            (-1.0, -2.0),
            (-1.0, 2.0),
            (0.0, -2.0),
            (0.0, 2.0),
            (1.0, -2.0),
            (1.0, 2.0)
        ]
    );
}

#[test]
fn pit_aligned_with_cell_edges_is_exactly_depth_inside_and_zero_outside() {
    // binary fractions: every edge is exact
    let h = 2f64.powi(-12);
    for (nx, ny) in [(16, 12), (15, 9), (16, 1)] {
        let g = Grid::new(
            nx,
            ny,
            -(nx as f64) / 2.0 * h,
            nx as f64 / 2.0 * h,
            -(ny as f64) / 2.0 * h,
            ny as f64 / 2.0 * h,
        );
        // a 4 x 2 cell pit whose edges sit on cell edges (odd nx: centre shifted half a cell)
        let cx = if nx % 2 == 1 { 0.5 * h } else { 0.0 };
        let cy = if ny % 2 == 1 { 0.5 * h } else { 0.0 };
        let length = if ny == 1 { f64::INFINITY } else { 2.0 * h };
        let out = sample(&one(pit(4.0 * h, length, D), (cx, cy)), &g, 0.0);
        let mut inside = 0;
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = (g.x(i), g.y(j));
                let v = out[g.idx(i, j)];
                if (x - cx).abs() < 2.0 * h && (y - cy).abs() < 0.5 * length {
                    assert_eq!(v, D, "cell ({i}, {j})");
                    inside += 1;
                } else {
                    assert_eq!(v, 0.0, "cell ({i}, {j})");
                }
            }
        }
        assert_eq!(inside, if ny == 1 { 4 } else { 8 });
        // shifted by whole cells along x: still exact
        let out = sample(&one(pit(4.0 * h, length, D), (cx, cy)), &g, 3.0 * h);
        assert_eq!(out.iter().filter(|&&v| v == D).count(), inside);
        assert_eq!(out.iter().filter(|&&v| v == 0.0).count(), g.len() - inside);
    }
}

#[test]
fn moving_a_pit_by_a_small_fraction_of_a_cell_changes_the_field_a_little() {
    for g in grids() {
        let s = g.dx * 1e-3;
        let (w, l) = (0.29e-3, 0.33e-3);
        // put the rear edge half a step before a cell centre: a point sample jumps there
        let xc = g.x(g.nx / 2) - 0.5 * s - 0.5 * w;
        let surf = one(pit(w, l, D), (xc, 0.013e-3));
        let (a, b) = (sample(&surf, &g, 0.0), sample(&surf, &g, s));
        let change = a
            .iter()
            .zip(&b)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        assert!(change <= 1e-3 * D * (1.0 + 1e-9), "{change}");
        assert!(change >= 0.3e-3 * D, "the pit should move: {change}");
        // point sampling at the centres would jump by the full depth
        let jump = (0..g.ny)
            .flat_map(|j| (0..g.nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                (surf.depth_at(g.x(i), g.y(j), 0.0) - surf.depth_at(g.x(i), g.y(j), s)).abs()
            })
            .fold(0.0, f64::max);
        assert_eq!(jump, D);
    }
}

#[test]
fn moving_a_dent_by_a_small_fraction_of_a_cell_changes_the_field_a_little() {
    for g in grids() {
        let s = g.dx * 1e-3;
        let surf = one(dent(0.4e-3, 0.5e-3, D), (0.021e-3, -0.03e-3));
        let (a, b) = (sample(&surf, &g, 0.0), sample(&surf, &g, s));
        let change = a
            .iter()
            .zip(&b)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        // |d'| <= d pi / w: the average moves by at most that times s
        assert!(change <= D * PI / 0.4e-3 * s, "{change}");
        assert!(change > 0.0);
    }
}

#[test]
fn negative_depth_flips_the_sign_exactly() {
    let hm = HeightMap {
        depths: Array2::from_shape_fn((4, 6), |(j, i)| 1e-8 * (i as f64 - 0.3 * j as f64)),
        dx: 0.07e-3,
        dy: 0.09e-3,
    };
    let neg_hm = HeightMap {
        depths: hm.depths.mapv(|h| -h),
        ..hm.clone()
    };
    let p = Pattern {
        rows: 3,
        columns: 1,
        row_pitch: 0.3e-3,
        column_pitch: 0.0,
    };
    for g in grids() {
        let pairs = [
            (pit(0.2e-3, 0.3e-3, D), pit(0.2e-3, 0.3e-3, -D)),
            (
                pit(0.2e-3, f64::INFINITY, D),
                pit(0.2e-3, f64::INFINITY, -D),
            ),
            (dent(0.2e-3, 0.3e-3, D), dent(0.2e-3, 0.3e-3, -D)),
            (
                dent(0.2e-3, f64::INFINITY, D),
                dent(0.2e-3, f64::INFINITY, -D),
            ),
            (
                FeatureShape::HeightMap(hm.clone()),
                FeatureShape::HeightMap(neg_hm.clone()),
            ),
        ];
        for (pos, neg) in pairs {
            for pattern in [None, Some(p)] {
                let f = |shape: FeatureShape| {
                    Surface::new(vec![Feature {
                        shape,
                        centre: (0.05e-3, -0.02e-3),
                        pattern,
                    }])
                };
                let (a, b) = (
                    sample(&f(pos.clone()), &g, 0.017e-3),
                    sample(&f(neg.clone()), &g, 0.017e-3),
                );
                assert!(a.iter().any(|&v| v != 0.0));
                for (x, y) in a.iter().zip(&b) {
                    assert_eq!(*x, -*y, "{pos:?}");
                }
            }
        }
        let w = |amplitude| {
            one(
                FeatureShape::Waviness {
                    amplitude,
                    wavelength: 0.3e-3,
                },
                (0.01e-3, 0.0),
            )
        };
        let (a, b) = (sample(&w(D), &g, 0.0), sample(&w(-D), &g, 0.0));
        for (x, y) in a.iter().zip(&b) {
            assert_eq!(*x, -*y);
        }
    }
}

#[test]
fn a_groove_is_uniform_along_y() {
    for g in grids() {
        for shape in [
            pit(0.23e-3, f64::INFINITY, D),
            dent(0.23e-3, f64::INFINITY, D),
        ] {
            let out = sample(&one(shape.clone(), (0.031e-3, 0.2e-3)), &g, 0.012e-3);
            for j in 1..g.ny {
                assert_eq!(out[g.idx(0, j)..g.idx(0, j) + g.nx], out[..g.nx]);
            }
            // cross-section: depth * width (pit), depth * width / 2 (cosine groove)
            let area = out[..g.nx].iter().sum::<f64>() * g.dx;
            let exact = match shape {
                FeatureShape::Pit { .. } => D * 0.23e-3,
                _ => D * 0.23e-3 / 2.0,
            };
            assert!((area / exact - 1.0).abs() < 1e-13, "{area} vs {exact}");
        }
    }
}

#[test]
fn dent_volume_formula_is_the_integral_of_the_cosine_bump() {
    // independent check of the closed form: Simpson on int_0^1 (1 + cos(pi r))/2 2 pi r dr
    let n = 20000;
    let f = |r: f64| 0.5 * (1.0 + (PI * r).cos()) * 2.0 * PI * r;
    let h = 1.0 / n as f64;
    let mut s = f(0.0) + f(1.0);
    for k in 1..n {
        s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k as f64 * h);
    }
    let unit = s * h / 3.0; // volume over the unit disk, depth 1
    let (w, l) = (0.3e-3, 0.2e-3);
    let v = unit * w * l / 4.0 * D;
    let formula = dent(w, l, D).volume().unwrap();
    assert!((v / formula - 1.0).abs() < 1e-12, "{v} vs {formula}");
    // and not twice it (pi/4 instead of pi/8)
    assert!((D * w * l * PI / 4.0 * (1.0 - 4.0 / (PI * PI)) / formula - 2.0).abs() < 1e-12);
}

#[test]
fn dent_cell_averages_integrate_to_its_volume() {
    let mut gs = grids();
    // fine grids: the dent spans tens of cells (the 4-point rule on short intervals)
    gs.push(Grid::new(96, 80, -0.5e-3, 0.45e-3, -0.4e-3, 0.41e-3));
    gs.push(Grid::new(257, 200, -0.5e-3, 0.45e-3, -0.4e-3, 0.41e-3));
    for g in gs {
        for &(w, l, c) in &[
            (0.4e-3, 0.5e-3, (0.0, 0.0)),
            (0.37e-3, 0.21e-3, (0.0123e-3, -0.0456e-3)),
            // smaller than one cell: the whole dent inside a cell or across a few
            (0.5 * g.dx, 0.4 * g.dy, (g.x(3), g.y(2))),
            (
                0.9 * g.dx,
                1.3 * g.dy,
                (g.x(3) + 0.5 * g.dx, g.y(2) + 0.5 * g.dy),
            ),
        ] {
            let out = sample(&one(dent(w, l, D), c), &g, 0.0);
            let exact = dent(w, l, D).volume().unwrap();
            let v = volume(&out, &g);
            assert!(
                (v / exact - 1.0).abs() < 1e-13,
                "{g:?} {w} {l}: {}",
                v / exact - 1.0
            );
            assert!(out.iter().all(|&o| (0.0..=D).contains(&o)));
        }
    }
}

#[test]
fn dent_cell_averages_match_brute_force_averages() {
    let g = Grid::new(9, 7, -0.3e-3, 0.3e-3, -0.25e-3, 0.25e-3);
    let surf = one(dent(0.41e-3, 0.33e-3, D), (0.017e-3, -0.011e-3));
    let out = sample(&surf, &g, 0.0);
    let m = 400;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let mut s = 0.0;
            for q in 0..m {
                for p in 0..m {
                    let x = g.x_min + (i as f64 + (p as f64 + 0.5) / m as f64) * g.dx;
                    let y = g.y_min + (j as f64 + (q as f64 + 0.5) / m as f64) * g.dy;
                    s += surf.depth_at(x, y, 0.0);
                }
            }
            let brute = s / (m * m) as f64;
            assert!((out[g.idx(i, j)] - brute).abs() < 1e-6 * D, "({i}, {j})");
        }
    }
}

#[test]
fn waviness_is_the_exact_cosine_average_and_tends_to_the_point_value() {
    let (a, lambda, xc, shift) = (D, 0.27e-3, 0.031e-3, 0.0123e-3);
    let k = 2.0 * PI / lambda;
    let surf = one(
        FeatureShape::Waviness {
            amplitude: a,
            wavelength: lambda,
        },
        (xc, 0.7e-3),
    );
    let mut last = 0.0;
    for nx in [8, 16, 32, 64, 128, 256, 512, 1024] {
        let g = Grid::new(nx, 5, -1.0e-3, 1.1e-3, -0.3e-3, 0.4e-3);
        let out = sample(&surf, &g, shift);
        let mut err = 0.0f64;
        for i in 0..nx {
            // independent: composite GL on the cell
            let (x0, x1) = (g.x_min + i as f64 * g.dx, g.x_min + (i + 1) as f64 * g.dx);
            // (panels of an eighth of a wavelength: GL6 error ~1e-18)
            let quad = super::gl(4.0 * x0 / lambda, 4.0 * x1 / lambda, |t| {
                a * (2.0 * PI * (0.25 * t - (xc + shift) / lambda)).cos()
            }) * 0.25
                * lambda
                / g.dx;
            let z = 0.5 * k * g.dx;
            let formula = a * (k * (g.x(i) - xc - shift)).cos() * z.sin() / z;
            for j in 0..g.ny {
                let v = out[g.idx(i, j)];
                assert!((v - formula).abs() < 1e-14 * a, "{nx} {i}");
                assert!((v - quad).abs() < 1e-12 * a, "{nx} {i}: {v} vs {quad}");
            }
            err = err.max((out[i] - surf.depth_at(g.x(i), 0.0, shift)).abs());
        }
        // |1 - sinc z| <= z^2 / 6: second order in dx
        let z = 0.5 * k * g.dx;
        assert!(err <= a * z * z / 6.0 * (1.0 + 1e-9), "{nx}: {err}");
        last = err;
    }
    assert!(last < 1e-4 * a, "{last}");
}

fn map(ny: usize, nx: usize, f: impl Fn(usize, usize) -> f64) -> HeightMap {
    HeightMap {
        depths: Array2::from_shape_fn((ny, nx), |(j, i)| f(j, i)),
        dx: 0.05e-3,
        dy: 0.08e-3,
    }
}

#[test]
fn a_constant_height_map_samples_to_that_depth_inside_the_map() {
    let c = 3.0e-8;
    for g in grids() {
        let m = map(5, 7, |_, _| c);
        let (hx, hy) = (3.0 * m.dx, 2.0 * m.dy);
        let centre = (0.021e-3, -0.013e-3);
        let surf = one(FeatureShape::HeightMap(m), centre);
        let out = sample(&surf, &g, 0.0);
        let mut inside = 0;
        for j in 0..g.ny {
            for i in 0..g.nx {
                let v = out[g.idx(i, j)];
                let (x0, x1) = (g.x_min + i as f64 * g.dx, g.x_min + (i + 1) as f64 * g.dx);
                let (y0, y1) = (g.y_min + j as f64 * g.dy, g.y_min + (j + 1) as f64 * g.dy);
                let (mx0, mx1) = (centre.0 - hx, centre.0 + hx);
                let (my0, my1) = (centre.1 - hy, centre.1 + hy);
                if x0 >= mx0 && x1 <= mx1 && y0 >= my0 && y1 <= my1 {
                    // the map holds depths: a constant c samples to c
                    assert!((v - c).abs() < 1e-14 * c, "({i}, {j}): {v}");
                    inside += 1;
                } else if x1 <= mx0 || x0 >= mx1 || y1 <= my0 || y0 >= my1 {
                    assert_eq!(v, 0.0);
                } else {
                    assert!(v >= 0.0 && v <= c * (1.0 + 1e-14));
                }
            }
        }
        assert!(inside > 0 || g.dx > hx || g.dy > hy);
        let exact = c * 4.0 * hx * hy;
        assert!((volume(&out, &g) / exact - 1.0).abs() < 1e-13);
    }
}

#[test]
fn height_map_is_exact_for_bilinear_data_and_conserves_volume() {
    let bilinear = |x: f64, y: f64| 1e-8 * (1.0 + 3e3 * x - 2e3 * y + 4e7 * x * y);
    let (nx_m, ny_m) = (9, 6);
    let dx = 0.05e-3;
    let dy = 0.08e-3;
    let m = map(ny_m, nx_m, |j, i| {
        bilinear((i as f64 - 4.0) * dx, (j as f64 - 2.5) * dy)
    });
    // an irregular map too
    let rough = map(11, 13, |j, i| 1e-8 * ((i * 7 + j * 3) % 5) as f64 - 2e-8);
    for g in grids() {
        let out = sample(
            &one(FeatureShape::HeightMap(m.clone()), (0.0, 0.0)),
            &g,
            0.0,
        );
        for j in 0..g.ny {
            for i in 0..g.nx {
                let (x0, x1) = (g.x_min + i as f64 * g.dx, g.x_min + (i + 1) as f64 * g.dx);
                let (y0, y1) = (g.y_min + j as f64 * g.dy, g.y_min + (j + 1) as f64 * g.dy);
                if x0 >= -4.0 * dx && x1 <= 4.0 * dx && y0 >= -2.5 * dy && y1 <= 2.5 * dy {
                    let want = bilinear(g.x(i), g.y(j));
                    assert!((out[g.idx(i, j)] - want).abs() < 1e-12 * 1e-8, "({i}, {j})");
                }
            }
        }
        for shift in [0.0, 0.0137e-3] {
            let f = Feature::new(FeatureShape::HeightMap(rough.clone()), (-0.03e-3, 0.02e-3));
            let exact = f.volume().unwrap();
            // the rough map's volume nearly cancels: compare with the volume of |height|
            let scale = rough.depths.iter().map(|h| h.abs()).sum::<f64>() * rough.dx * rough.dy;
            let out = sample(&Surface::new(vec![f]), &g, shift);
            assert!((volume(&out, &g) - exact).abs() < 1e-14 * scale);
        }
    }
}

#[test]
fn height_map_cell_averages_match_brute_force_averages() {
    let g = Grid::new(7, 6, -0.35e-3, 0.33e-3, -0.5e-3, 0.45e-3);
    let rough = map(11, 13, |j, i| 1e-8 * ((i * 7 + j * 3) % 5) as f64 - 2e-8);
    let surf = one(FeatureShape::HeightMap(rough), (0.011e-3, -0.023e-3));
    let out = sample(&surf, &g, 0.004e-3);
    let m = 300;
    for j in 0..g.ny {
        for i in 0..g.nx {
            let mut s = 0.0;
            for q in 0..m {
                for p in 0..m {
                    let x = g.x_min + (i as f64 + (p as f64 + 0.5) / m as f64) * g.dx;
                    let y = g.y_min + (j as f64 + (q as f64 + 0.5) / m as f64) * g.dy;
                    s += surf.depth_at(x, y, 0.004e-3);
                }
            }
            let brute = s / (m * m) as f64;
            // the map's zero outside is a jump: midpoint error ~ 1/m of its height
            assert!((out[g.idx(i, j)] - brute).abs() < 2e-10, "({i}, {j})");
        }
    }
}

#[test]
fn features_outside_the_grid_leave_it_smooth_and_overlaps_add() {
    let g = Grid::new(16, 8, -1e-3, 1e-3, -0.5e-3, 0.5e-3);
    let far = Surface::new(vec![
        Feature::new(pit(0.1e-3, 0.1e-3, D), (5e-3, 0.0)),
        Feature::new(dent(0.1e-3, 0.1e-3, D), (0.0, -3e-3)),
    ]);
    assert!(sample(&far, &g, 0.0).iter().all(|&v| v == 0.0));
    let a = one(pit(0.3e-3, 0.2e-3, D), (0.01e-3, 0.0));
    let b = one(dent(0.3e-3, 0.2e-3, -D), (0.05e-3, 0.02e-3));
    let both = Surface::new(vec![a.features[0].clone(), b.features[0].clone()]);
    let (sa, sb, s2) = (
        sample(&a, &g, 0.0),
        sample(&b, &g, 0.0),
        sample(&both, &g, 0.0),
    );
    for k in 0..g.len() {
        assert!((s2[k] - sa[k] - sb[k]).abs() < 1e-15 * D);
    }
}

#[test]
fn check_rejects_bad_parameters() {
    let ok = Feature::new(pit(1e-4, f64::INFINITY, -D), (0.0, 0.0));
    assert!(ok.check().is_ok());
    let bad = [
        Feature::new(pit(0.0, 1e-4, D), (0.0, 0.0)),
        Feature::new(dent(1e-4, -1e-4, D), (0.0, 0.0)),
        Feature::new(pit(1e-4, 1e-4, f64::NAN), (0.0, 0.0)),
        Feature::new(pit(1e-4, 1e-4, D), (f64::INFINITY, 0.0)),
        Feature::new(
            FeatureShape::Waviness {
                amplitude: D,
                wavelength: 0.0,
            },
            (0.0, 0.0),
        ),
        Feature::new(
            FeatureShape::Waviness {
                amplitude: D,
                wavelength: 1e-4,
            },
            (0.0, 0.0),
        )
        .with_pattern(Pattern {
            rows: 2,
            columns: 1,
            row_pitch: 1e-4,
            column_pitch: 0.0,
        }),
        Feature::new(pit(1e-4, 1e-4, D), (0.0, 0.0)).with_pattern(Pattern {
            rows: 2,
            columns: 1,
            row_pitch: 0.0,
            column_pitch: 0.0,
        }),
        Feature::new(FeatureShape::HeightMap(map(1, 5, |_, _| 0.0)), (0.0, 0.0)),
    ];
    for f in bad {
        assert!(f.check().is_err(), "{f:?}");
    }
    let s = Surface::new(vec![ok, Feature::new(pit(0.0, 1e-4, D), (0.0, 0.0))]);
    assert!(s.check().unwrap_err().starts_with("feature 1:"));
}

/// `cargo test -p ehl --lib surface::tests::timing -- --ignored --nocapture`
#[test]
#[ignore]
fn timing_256x256() {
    use std::time::Instant;
    let b = 0.2e-3;
    let g = Grid::new(256, 256, -2.5 * b, 1.5 * b, -2.0 * b, 2.0 * b);
    let mut out = vec![0.0; g.len()];
    let nine = Surface::new(vec![Feature::new(pit(0.1e-3, 0.1e-3, D), (0.0, 0.0))
        .with_pattern(Pattern {
            rows: 3,
            columns: 3,
            row_pitch: 0.2e-3,
            column_pitch: 0.2e-3,
        })]);
    let nine_dents = Surface::new(vec![Feature::new(dent(0.1e-3, 0.1e-3, D), (0.0, 0.0))
        .with_pattern(Pattern {
            rows: 3,
            columns: 3,
            row_pitch: 0.2e-3,
            column_pitch: 0.2e-3,
        })]);
    let wavy = one(
        FeatureShape::Waviness {
            amplitude: D,
            wavelength: 0.1e-3,
        },
        (0.0, 0.0),
    );
    for (name, s) in [
        ("9 pits", &nine),
        ("9 dents", &nine_dents),
        ("waviness", &wavy),
    ] {
        let n = 200;
        let t = Instant::now();
        for k in 0..n {
            s.cell_averages(&g, k as f64 * 1e-7, &mut out);
        }
        println!(
            "{name}: {:.1} us per sampling of 256 x 256 (cell_averages incl. zero fill)",
            t.elapsed().as_secs_f64() / n as f64 * 1e6
        );
    }
}
