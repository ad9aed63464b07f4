//! The gear set in motion as an animated GIF, for a lecturer's slides.
//!
//! The frames are not captured from the running animation: the plan
//! ([`gif_plan`]) steps the animation's instant through one period of the
//! orbit (its period in mesh periods, from the steady state), at an even
//! stride of samples that divides the period, so the frame after the last
//! is the first again and the file loops without a jump. The web layer
//! draws each planned instant's [`Scene`] with the canvas's own calls
//! (the page's drawing, words included) and hands the pixels to a
//! [`GifWriter`], which is plain Rust: per frame a palette of the colours
//! it uses most (the scene's flat fills and lines, exactly), every other
//! pixel (the edges' blends) mapped to its nearest palette colour, and
//! the `gif` crate's LZW encoder. A motion that does not repeat gets
//! [`GIF_OPEN_PERIODS`] mesh periods, and the plan says the loop jumps.

use super::Page;
use crate::gearset::{AnimClock, BodyKind, GearSet};
use crate::scene::{gear_scene, Item, Scene, SubPath};
use figures::protocol::OmegaResult;
use figures::views::ViewId;
use rustc_hash::FxHashMap;

/// The most frames in a GIF: a period of eight mesh periods still gets
/// 8 frames a mesh period, and the file stays within a few megabytes.
pub const GIF_MAX_FRAMES: usize = 64;

/// The fewest hundredths of a second a frame shows: browsers show a GIF
/// frame of 0 or 1 hundredth for a tenth of a second.
pub const GIF_MIN_DELAY_CS: u16 = 2;

/// The mesh periods a GIF of a motion that does not repeat shows: a
/// short stretch at the frame rate of a periodic one's, rather than the
/// whole window in jerks.
pub const GIF_OPEN_PERIODS: usize = 4;

/// The GIF's size (pixels): the page's gear set canvas.
pub const GIF_SIZE: (u32, u32) = (760, 600);

/// What the GIF shows: the instants, how long each frame shows, and
/// whether the loop closes.
#[derive(Debug, Clone, PartialEq)]
pub struct GifPlan {
    /// Each frame's position in the animation's window (samples).
    pub positions: Vec<f64>,
    /// How long each frame shows (hundredths of a second).
    pub delay_cs: u16,
    /// Samples from one frame to the next.
    pub stride: usize,
    /// The span shown (samples): one period of the orbit, or
    /// [`GIF_OPEN_PERIODS`] of a motion that does not repeat.
    pub span: usize,
    /// Whether the span is a period of the orbit (the loop closes).
    pub closes: bool,
}

/// The plan for the steady state `r` shown at `periods_per_s` mesh
/// periods a second (the page's slow motion); `None` before any motion.
pub fn gif_plan(r: &OmegaResult, periods_per_s: f64) -> Option<GifPlan> {
    let len = r.anim.x_um.first().map_or(0, Vec::len);
    let spp = r.samples_per_period.max(1) as usize;
    if len == 0 {
        return None;
    }
    let period = r.period.map(|p| p.max(1) as usize * spp);
    let (span, closes) = match period {
        Some(p) if p <= len => (p, true),
        _ => ((GIF_OPEN_PERIODS * spp).min(len), false),
    };
    // The smallest stride that keeps to GIF_MAX_FRAMES and divides the
    // span (a whole number of frames a period).
    let stride = (span.div_ceil(GIF_MAX_FRAMES)..=span)
        .find(|s| span % s == 0)
        .unwrap_or(span);
    let speed = if periods_per_s.is_finite() && periods_per_s > 0.0 {
        periods_per_s
    } else {
        AnimClock::default().periods_per_s
    };
    let delay = (100.0 * stride as f64 / (spp as f64 * speed)).round();
    let delay_cs = delay.clamp(f64::from(GIF_MIN_DELAY_CS), f64::from(u16::MAX)) as u16;
    Some(GifPlan {
        positions: (0..span / stride).map(|k| (k * stride) as f64).collect(),
        delay_cs,
        stride,
        span,
        closes,
    })
}

/// Why a GIF could not be made.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum GifError {
    /// No frames, or a frame of the wrong size.
    #[error("the animation's frames could not be drawn ({0})")]
    Frames(String),
    /// The encoder refused (a size over 65 535 pixels).
    #[error("the GIF could not be encoded: {0}")]
    Encode(String),
    /// The selected state's motion is not there yet.
    #[error("The GIF is made from the motion at the selected speed, which is still being computed; try again once it shows.")]
    NotReady,
    /// The model's gear set has no drawing.
    #[error("the gear set of this model cannot be drawn")]
    NoScene,
    /// The browser refused a part the GIF needs (a canvas, a frame's
    /// pixels, the file): the message names it.
    #[error("the browser {0}")]
    Browser(&'static str),
}

/// A palette (at most 256 colours) for RGBA `frames`: the colours most
/// pixels have, in order of use (ties by colour, so the palette does not
/// depend on a hash's order).
fn palette(frames: &[&[u8]]) -> Vec<[u8; 3]> {
    let mut count: FxHashMap<[u8; 3], u64> = FxHashMap::default();
    for f in frames {
        for px in f.chunks_exact(4) {
            *count.entry([px[0], px[1], px[2]]).or_insert(0) += 1;
        }
    }
    let mut by_use: Vec<([u8; 3], u64)> = count.into_iter().collect();
    by_use.sort_unstable_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    by_use.into_iter().take(256).map(|(c, _)| c).collect()
}

/// The palette entry nearest `c` (squared distance in RGB).
fn nearest(palette: &[[u8; 3]], c: [u8; 3]) -> u8 {
    let d = |p: &[u8; 3]| -> i32 {
        (0..3)
            .map(|i| (i32::from(p[i]) - i32::from(c[i])).pow(2))
            .sum()
    };
    palette
        .iter()
        .enumerate()
        .min_by_key(|(_, p)| d(p))
        .map_or(0, |(i, _)| i as u8)
}

/// An animated GIF written a frame at a time (the web layer spreads the
/// frames over animation frames, so no task of the page's main thread
/// takes long), looping for ever. Each frame has its own palette: the
/// colours it uses most, exactly, every other pixel mapped to its
/// nearest palette colour.
pub struct GifWriter {
    enc: gif::Encoder<Vec<u8>>,
    size: (u16, u16),
    delay_cs: u16,
    frames: usize,
}

fn encode_error(e: gif::EncodingError) -> GifError {
    GifError::Encode(e.to_string())
}

impl GifWriter {
    /// A GIF of frames of `size` pixels, each shown `delay_cs` hundredths
    /// of a second.
    pub fn new(size: (u32, u32), delay_cs: u16) -> Result<Self, GifError> {
        let size = (
            u16::try_from(size.0).map_err(|e| GifError::Encode(e.to_string()))?,
            u16::try_from(size.1).map_err(|e| GifError::Encode(e.to_string()))?,
        );
        let mut enc = gif::Encoder::new(Vec::new(), size.0, size.1, &[]).map_err(encode_error)?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(encode_error)?;
        Ok(GifWriter {
            enc,
            size,
            delay_cs,
            frames: 0,
        })
    }

    /// Adds a frame of RGBA pixels (opaque: the alpha is ignored).
    pub fn push(&mut self, rgba: &[u8]) -> Result<(), GifError> {
        let (w, h) = self.size;
        let n = usize::from(w) * usize::from(h) * 4;
        if rgba.len() != n {
            return Err(GifError::Frames(format!(
                "a frame of {} bytes, {n} expected",
                rgba.len()
            )));
        }
        let pal = palette(&[rgba]);
        let mut index: FxHashMap<[u8; 3], u8> =
            pal.iter().enumerate().map(|(i, c)| (*c, i as u8)).collect();
        let mut last: Option<([u8; 3], u8)> = None;
        let buffer: Vec<u8> = rgba
            .chunks_exact(4)
            .map(|px| {
                let c = [px[0], px[1], px[2]];
                match last {
                    Some((lc, li)) if lc == c => li,
                    _ => {
                        let i = *index.entry(c).or_insert_with(|| nearest(&pal, c));
                        last = Some((c, i));
                        i
                    }
                }
            })
            .collect();
        let frame = gif::Frame {
            delay: self.delay_cs,
            width: w,
            height: h,
            palette: Some(pal.iter().flatten().copied().collect()),
            buffer: buffer.into(),
            ..gif::Frame::default()
        };
        self.enc.write_frame(&frame).map_err(encode_error)?;
        self.frames += 1;
        Ok(())
    }

    /// The frames written so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// The file's bytes (no frame: an error).
    pub fn finish(self) -> Result<Vec<u8>, GifError> {
        if self.frames == 0 {
            return Err(GifError::Frames("no frame".into()));
        }
        self.enc.into_inner().map_err(encode_error)
    }
}

/// An animated GIF, looping for ever, of RGBA `frames` of `size` pixels
/// (opaque), each shown `delay_cs` hundredths of a second.
pub fn encode_gif(frames: &[&[u8]], size: (u32, u32), delay_cs: u16) -> Result<Vec<u8>, GifError> {
    let mut w = GifWriter::new(size, delay_cs)?;
    for f in frames {
        w.push(f)?;
    }
    w.finish()
}

/// The gear set as a GIF's frame shows it: seen from the carrier (the
/// planets' pins stand still, every gear turns one tooth a mesh period,
/// so the picture repeats with the motion's period), without the radial
/// marks that show each gear's turning on the page (a mark turns by a
/// tooth a period and would jump where the GIF loops).
pub fn loop_scene(set: &GearSet, r: &OmegaResult, clock: &AnimClock, size: (f64, f64)) -> Scene {
    let mut seen = set.clone();
    let carrier = seen.carrier_rad;
    seen.carrier_rad = 0.0;
    for b in seen
        .bodies
        .iter_mut()
        .filter(|b| b.kind != BodyKind::Planet)
    {
        b.spin_rad -= carrier;
    }
    let mut scene = gear_scene(&seen, r, clock, size);
    // Each body's outline is followed by its mark, a line of two points.
    let mut items = Vec::with_capacity(scene.items.len());
    let mut after_outline = false;
    for item in scene.items.drain(..) {
        let (outline, mark) = match &item {
            Item::Shape { parts, .. } => (
                matches!(parts.first(), Some(SubPath::Polygon(_))),
                matches!(parts.as_slice(), [SubPath::Polyline(p)] if p.len() == 2),
            ),
            _ => (false, false),
        };
        if !(after_outline && mark) {
            items.push(item);
        }
        after_outline = outline;
    }
    // Said on the picture, since the page's animation turns the carrier.
    items.push(Item::Text {
        at: glam::DVec2::new(10.0, 18.0),
        text: "Seen from the carrier".into(),
        color: "#5a6573".into(),
    });
    scene.items = items;
    scene
}

impl Page {
    /// The GIF's plan at the page's animation speed, and the file's name
    /// (as the other exports': view, mesh, Ω); `None` before any motion.
    pub fn gif_plan(&self) -> Option<(GifPlan, String)> {
        let r = self.ctl.main().omega.as_ref()?;
        let plan = gif_plan(r, self.anim.clock.periods_per_s)?;
        let name = self.ctl.file_name(ViewId::Time, None, "gif");
        let name = match name.strip_prefix("gearshock-time") {
            Some(rest) => format!("gearshock-anim{rest}"),
            None => name,
        };
        Some((plan, name))
    }

    /// The gear set at position `pos` of the animation's window on a
    /// canvas of `size` pixels (a GIF's frame), seen from the carrier
    /// ([`loop_scene`]); `None` before any motion.
    pub fn gif_scene(&mut self, pos: f64, size: (f64, f64)) -> Option<Scene> {
        self.anim_set()?;
        let (Some((_, set)), Some(r)) = (self.anim.set.as_ref(), self.ctl.main().omega.as_ref())
        else {
            return None;
        };
        let clock = AnimClock {
            pos,
            playing: true,
            periods_per_s: self.anim.clock.periods_per_s,
        };
        Some(loop_scene(set, r, &clock, size))
    }

    /// The GIF made (`bytes` long): in the status, and said in the
    /// messages when its loop jumps.
    pub fn gif_made(&mut self, plan: &GifPlan, bytes: usize) {
        self.anim.gif = serde_json::json!({
            "frames": plan.positions.len(),
            "delay_cs": plan.delay_cs,
            "stride": plan.stride,
            "span": plan.span,
            "closes": plan.closes,
            "bytes": bytes,
        });
        if !plan.closes {
            self.issue(format!(
                "The motion does not repeat, so the GIF shows {GIF_OPEN_PERIODS} mesh periods of it and jumps where it loops."
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use figures::views::test_support::omega_result;

    /// The fixture with an animation window: every mesh of the default
    /// set following the period-1 history, its last 12 periods.
    fn result(period: Option<u32>) -> OmegaResult {
        let mut r = omega_result();
        r.period = period;
        let spp = r.samples_per_period as usize;
        let start = r.x_um.len() - 12 * spp;
        r.anim.start_sample = start as u32;
        r.anim.x_um = vec![r.x_um[start..].to_vec(); 9];
        r.anim.backlash_um = vec![100.0; 9];
        r
    }

    /// A test's rasterizer: each filled polygon and circle of the scene,
    /// point-sampled at pixel centres (the browser draws the real frames).
    fn raster(scene: &Scene, (w, h): (u32, u32)) -> Vec<u8> {
        let mut px = vec![255u8; (w * h * 4) as usize];
        // Each colour's text hashed to a colour: distinct enough here.
        let rgb = |c: &str| -> [u8; 3] {
            let h = c.bytes().fold(2166136261u32, |h, b| {
                (h ^ u32::from(b)).wrapping_mul(16777619)
            });
            [(h >> 16) as u8, (h >> 8) as u8, h as u8]
        };
        let inside = |pts: &[glam::DVec2], x: f64, y: f64| {
            let mut c = false;
            for i in 0..pts.len() {
                let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
                if (a.y > y) != (b.y > y) && x < a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x) {
                    c = !c;
                }
            }
            c
        };
        for item in &scene.items {
            let Item::Shape {
                parts,
                fill: Some(fill),
                ..
            } = item
            else {
                continue;
            };
            let color = rgb(fill);
            for part in parts {
                let (lo, hi) = match part {
                    SubPath::Polygon(pts) => pts.iter().fold(
                        (glam::DVec2::splat(f64::MAX), glam::DVec2::splat(f64::MIN)),
                        |(lo, hi), q| (lo.min(*q), hi.max(*q)),
                    ),
                    SubPath::Circle { c, r } => (*c - *r, *c + *r),
                    _ => continue,
                };
                let xs = lo.x.max(0.0) as u32..(hi.x.ceil().max(0.0) as u32).min(w);
                for y in lo.y.max(0.0) as u32..(hi.y.ceil().max(0.0) as u32).min(h) {
                    for x in xs.clone() {
                        let (fx, fy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                        let hit = match part {
                            SubPath::Polygon(pts) => inside(pts, fx, fy),
                            SubPath::Circle { c, r } => c.distance(glam::DVec2::new(fx, fy)) < *r,
                            _ => false,
                        };
                        if hit {
                            let k = ((y * w + x) * 4) as usize;
                            px[k..k + 3].copy_from_slice(&color);
                        }
                    }
                }
            }
        }
        px
    }

    #[test]
    fn a_period_one_orbit_gives_one_mesh_period_in_even_steps() {
        let r = result(Some(1));
        let plan = gif_plan(&r, 0.5).unwrap();
        // 64 samples a period: 64 frames of one sample, each 1/64 of the
        // 2 s a mesh period takes at 0.5 periods a second (3 hundredths).
        assert_eq!((plan.span, plan.stride, plan.positions.len()), (64, 1, 64));
        assert_eq!(plan.delay_cs, 3);
        assert!(plan.closes);
        // Period 3 at 64 samples: 192 samples in 64 frames of 3.
        let plan = gif_plan(&result(Some(3)), 0.5).unwrap();
        assert_eq!((plan.span, plan.stride, plan.positions.len()), (192, 3, 64));
        assert_eq!(plan.delay_cs, 9);
        // Not periodic: four mesh periods, and the loop jumps; at 2
        // periods a second a frame of 4 samples shows 1/32 s (3 hundredths).
        let plan = gif_plan(&result(None), 2.0).unwrap();
        assert_eq!((plan.span, plan.stride), (256, 4));
        assert!(!plan.closes);
        assert_eq!(plan.delay_cs, 3);
        // At 8 periods a second the frames would flash by: 2 hundredths.
        assert_eq!(
            gif_plan(&result(None), 8.0).unwrap().delay_cs,
            GIF_MIN_DELAY_CS
        );
        let mut none = result(Some(1));
        none.anim.x_um.clear();
        assert!(gif_plan(&none, 0.5).is_none());
    }

    #[test]
    fn the_gif_decodes_to_the_planned_frames_that_move_and_close_the_loop() {
        let mut page = Page::new(crate::controller::Controller::new("", 0.0).0, false);
        let meshes = page.ctl().model().map_or(0, |m| m.system.meshes.len());
        let mut r = result(Some(1));
        r.anim.x_um.resize(meshes, r.anim.x_um[0].clone());
        r.anim.backlash_um.resize(meshes, 100.0);
        let id = page.ctl().main().omega_status().id;
        let reply = figures::protocol::FromWorker::Omega {
            id,
            result: Box::new(r),
        };
        page.worker_message(0, &figures::protocol::encode(&reply), 1.0);
        let (plan, name) = page.gif_plan().unwrap();
        assert_eq!(name, "gearshock-anim-s1a1-omega0.84.gif");
        // Small frames keep the test's rasterizer quick.
        let size = (190u32, 150u32);
        let sz = (f64::from(size.0), f64::from(size.1));
        let frames: Vec<Vec<u8>> = plan
            .positions
            .iter()
            .map(|&p| raster(&page.gif_scene(p, sz).unwrap(), size))
            .collect();
        // The frame after the last is the first: the loop closes.
        let after = raster(&page.gif_scene(plan.span as f64, sz).unwrap(), size);
        let differ = after.iter().zip(&frames[0]).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "the frame after the last differs from the first");
        let refs: Vec<&[u8]> = frames.iter().map(Vec::as_slice).collect();
        let bytes = encode_gif(&refs, size, plan.delay_cs).unwrap();
        assert_eq!(&bytes[..6], b"GIF89a");
        // Decoded with the same crate: the size, the count, the delays,
        // the loop for ever, and frames that differ (the gears turn).
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::RGBA);
        let mut d = opts.read_info(bytes.as_slice()).unwrap();
        assert_eq!((u32::from(d.width()), u32::from(d.height())), size);
        let mut decoded = Vec::new();
        while let Some(f) = d.read_next_frame().unwrap() {
            assert_eq!(f.delay, plan.delay_cs);
            decoded.push(f.buffer.to_vec());
        }
        assert_eq!(d.repeat(), gif::Repeat::Infinite);
        assert_eq!(decoded.len(), plan.positions.len());
        // The test's frames have a few flat colours: the palette keeps them exactly.
        assert!(decoded[0] == frames[0] && decoded[17] == frames[17]);
        // The gears turn a tooth a period: a quarter period on, the frame differs.
        assert!(decoded[0] != decoded[16]);
        let mut distinct = decoded.clone();
        distinct.sort();
        distinct.dedup();
        assert!(distinct.len() >= 8, "{} distinct frames", distinct.len());
    }

    #[test]
    fn colours_beyond_the_palette_map_to_the_nearest() {
        // 255 colours used three times (even greys, even reds), then odd
        // greys used once: one takes the last place, the rest the nearest
        // even grey, one step away in each channel.
        let mut colours: Vec<[u8; 3]> = Vec::new();
        for g in (0..=254u8).step_by(2) {
            colours.extend([[g, g, g]; 3]);
            if g > 0 {
                colours.extend([[g, 0, 0]; 3]);
            }
        }
        colours.extend((1..=255u8).step_by(2).map(|g| [g, g, g]));
        let f: Vec<u8> = colours
            .iter()
            .flat_map(|c| [c[0], c[1], c[2], 255])
            .collect();
        let size = (colours.len() as u32, 1);
        let bytes = encode_gif(&[&f], size, 5).unwrap();
        let mut opts = gif::DecodeOptions::new();
        opts.set_color_output(gif::ColorOutput::RGBA);
        let mut d = opts.read_info(bytes.as_slice()).unwrap();
        let frame = d.read_next_frame().unwrap().unwrap();
        let worst = frame
            .buffer
            .chunks_exact(4)
            .zip(f.chunks_exact(4))
            .flat_map(|(a, b)| (0..3).map(move |i| (i32::from(a[i]) - i32::from(b[i])).abs()))
            .max()
            .unwrap();
        assert_eq!(worst, 1);
        assert_eq!(
            encode_gif(&[&f[..8]], size, 5),
            Err(GifError::Frames(format!(
                "a frame of 8 bytes, {} expected",
                f.len()
            )))
        );
        assert_eq!(
            encode_gif(&[], size, 5),
            Err(GifError::Frames("no frame".into()))
        );
    }
}
