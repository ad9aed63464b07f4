//! The plotters backend of the page's canvases: `plotters-canvas`'s
//! `CanvasBackend` for every drawing call, but text measured with the
//! canvas's own `measureText`. On wasm32 plotters measures a label by
//! adding a span to the page and reading its size, a forced layout of the
//! whole page per label: some 300 per page load, up to 36 ms each, all on
//! the main thread.

use figures::plots::css;
use figures::plots::decimate::{crisp_line, long_path, polylines_path};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
};
use plotters_canvas::CanvasBackend;
use web_sys::{CanvasRenderingContext2d, HtmlCanvasElement, Path2d};

type Error = DrawingErrorKind<<CanvasBackend as DrawingBackend>::ErrorType>;

/// The most text sizes [`MEASURED`] keeps before it starts again.
const MEASURED_MAX: usize = 4096;

thread_local! {
    /// Text sizes measured, by CSS font and text: a redraw asks again for
    /// the same tick labels and titles, and each measurement set the
    /// canvas's font twice (a font string parsed each time). The page's
    /// fonts are the system's generic families, whose metrics do not
    /// change while the page is open.
    static MEASURED: std::cell::RefCell<std::collections::HashMap<(String, String), (u32, u32)>> =
        std::cell::RefCell::new(std::collections::HashMap::new());
}

/// Drawing calls waiting to be made as one ([`Canvas::flush`]).
enum Batch {
    /// Nothing waits.
    Empty,
    /// Filled opaque circles of one colour: centres and radii.
    Dots {
        color: BackendColor,
        dots: Vec<(BackendCoord, u32)>,
    },
    /// Opaque lines and short paths of one colour and width, as polylines
    /// in canvas coordinates.
    Strokes {
        color: BackendColor,
        width: u32,
        paths: Vec<Vec<(f64, f64)>>,
    },
}

/// A canvas backend whose text sizes come from `measureText`.
pub(super) struct Canvas {
    inner: CanvasBackend,
    ctx: CanvasRenderingContext2d,
    /// The drawing's size, where it is not the canvas's (present mode).
    size: Option<(u32, u32)>,
    /// What waits to be drawn in one call.
    batch: Batch,
}

impl Canvas {
    /// The backend of `canvas`, if it has a 2D context.
    pub(super) fn new(canvas: &HtmlCanvasElement) -> Option<Self> {
        Self::scaled(canvas, None, 1.0)
    }

    /// The backend of `canvas` for a drawing of `size` pixels (the
    /// canvas's own where `None`), each `scale` canvas pixels wide: the
    /// context's transform scales every line and word, so they are drawn
    /// sharp at the canvas's resolution.
    pub(super) fn scaled(
        canvas: &HtmlCanvasElement,
        size: Option<(u32, u32)>,
        scale: f64,
    ) -> Option<Self> {
        let ctx = super::ctx2d(canvas)?;
        super::check(ctx.set_transform(scale, 0.0, 0.0, scale, 0.0, 0.0));
        let inner = CanvasBackend::with_canvas_object(canvas.clone())?;
        Some(Self {
            inner,
            ctx,
            size,
            batch: Batch::Empty,
        })
    }

    /// Makes the waiting calls as one. plotters-canvas sets the colour,
    /// begins a path, draws and fills or strokes per circle, line and
    /// path (four or more calls into JavaScript, the colour formatted as
    /// text each time): a family's six Poincaré sections of 1000 periods
    /// were 6 000 fills, a dotted line across a plot 140 strokes.
    /// Opaque shapes of one colour drawn together cover the same pixels
    /// as one by one. Every other drawing call flushes first, so the
    /// order of what is drawn is kept.
    fn flush(&mut self) -> Result<(), Error> {
        match std::mem::replace(&mut self.batch, Batch::Empty) {
            Batch::Empty => Ok(()),
            Batch::Dots { color, dots } => self.fill_dots(color, &dots),
            Batch::Strokes {
                color,
                width,
                paths,
            } => {
                self.stroke_paths(color, width, &paths);
                Ok(())
            }
        }
    }

    /// Fills `dots` in `color`: one path string of the circles, two arcs
    /// each, parsed once, and one fill.
    fn fill_dots(
        &mut self,
        color: BackendColor,
        dots: &[(BackendCoord, u32)],
    ) -> Result<(), Error> {
        self.ctx.set_fill_style_str(&css::color(color));
        let mut d = String::with_capacity(40 * dots.len());
        for &((x, y), r) in dots {
            use std::fmt::Write;
            let (x, y, r) = (i64::from(x), i64::from(y), i64::from(r));
            let _ = write!(
                d,
                "M{} {}a{r} {r} 0 1 0 {} 0a{r} {r} 0 1 0 {} 0z",
                x + r,
                y,
                -2 * r,
                2 * r
            );
        }
        if let Ok(p2d) = Path2d::new_with_path_string(&d) {
            self.ctx.fill_with_path_2d(&p2d);
            return Ok(());
        }
        // The browser refused the path: each circle the plotters-canvas
        // way, which reports why it fails.
        for &(center, r) in dots {
            self.inner.draw_circle(center, r, &color, true)?;
        }
        Ok(())
    }

    /// Strokes `paths` in `color` and `width`: one path string, one stroke.
    fn stroke_paths(&mut self, color: BackendColor, width: u32, paths: &[Vec<(f64, f64)>]) {
        self.ctx.set_stroke_style_str(&css::color(color));
        self.ctx.set_line_width(f64::from(width));
        if let Ok(p2d) = Path2d::new_with_path_string(&polylines_path(paths)) {
            self.ctx.stroke_with_path(&p2d);
            return;
        }
        // The browser refused the path string: one path of calls.
        self.ctx.begin_path();
        for path in paths {
            let mut pts = path.iter();
            if let Some(&(x, y)) = pts.next() {
                self.ctx.move_to(x, y);
            }
            for &(x, y) in pts {
                self.ctx.line_to(x, y);
            }
        }
        self.ctx.stroke();
    }

    /// Adds an opaque polyline of `style` to the strokes waiting, or
    /// flushes what waits and starts a new batch with it.
    fn stroke_later<S: BackendStyle>(
        &mut self,
        path: Vec<(f64, f64)>,
        style: &S,
    ) -> Result<(), Error> {
        let (color, width) = (style.color(), style.stroke_width());
        if let Batch::Strokes {
            color: c,
            width: w,
            paths,
        } = &mut self.batch
        {
            if c.rgb == color.rgb && *w == width {
                paths.push(path);
                return Ok(());
            }
        }
        self.flush()?;
        self.batch = Batch::Strokes {
            color,
            width,
            paths: vec![path],
        };
        Ok(())
    }
}

/// Shapes still waiting when a drawing ends without `present` are drawn.
impl Drop for Canvas {
    fn drop(&mut self) {
        // Nothing is left to report a failure to.
        let _ = self.flush();
    }
}

impl DrawingBackend for Canvas {
    type ErrorType = <CanvasBackend as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.size.unwrap_or_else(|| self.inner.get_size())
    }

    fn ensure_prepared(&mut self) -> Result<(), Error> {
        self.flush()?;
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), Error> {
        self.flush()?;
        self.inner.present()
    }

    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Result<(), Error> {
        self.flush()?;
        self.inner.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), Error> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        if color.alpha < 1.0 {
            self.flush()?;
            return self.inner.draw_line(from, to, style);
        }
        self.stroke_later(crisp_line(from, to), style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), Error> {
        self.flush()?;
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }

    /// One `Path2D` from an SVG path string and one stroke: plotters-canvas
    /// makes a JavaScript call per point (`lineTo`), some hundreds of
    /// thousands for a family's long chaotic orbits. Short paths
    /// ([`long_path`]), and any the browser refuses as a path string, go
    /// the plotters-canvas way.
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), Error> {
        if style.color().alpha == 0.0 {
            return Ok(());
        }
        let pts: Vec<BackendCoord> = path.into_iter().collect();
        let long = long_path(&pts);
        if long.is_none() && style.color().alpha >= 1.0 {
            let path = pts
                .iter()
                .map(|&(x, y)| (f64::from(x), f64::from(y)))
                .collect();
            return self.stroke_later(path, style);
        }
        self.flush()?;
        let Some(Ok(p2d)) = long.map(|d| Path2d::new_with_path_string(&d)) else {
            return self.inner.draw_path(pts, style);
        };
        self.ctx.set_stroke_style_str(&css::color(style.color()));
        self.ctx.set_line_width(f64::from(style.stroke_width()));
        self.ctx.stroke_with_path(&p2d);
        Ok(())
    }

    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), Error> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        // Translucent circles overlap visibly: drawn one by one.
        if !fill || color.alpha < 1.0 {
            self.flush()?;
            return self.inner.draw_circle(center, radius, style, fill);
        }
        if let Batch::Dots { color: c, dots } = &mut self.batch {
            if c.rgb == color.rgb {
                dots.push((center, radius));
                return Ok(());
            }
        }
        self.flush()?;
        self.batch = Batch::Dots {
            color,
            dots: vec![(center, radius)],
        };
        Ok(())
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), Error> {
        self.flush()?;
        self.inner.fill_polygon(vert, style)
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), Error> {
        self.flush()?;
        self.inner.draw_text(text, style, pos)
    }

    /// The text's advance width and its font's line height (ascent plus
    /// descent, what a span of it measures), in the font `draw_text` sets.
    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), Error> {
        let font = css::font(style);
        let key = (font, text.to_string());
        if let Some(size) = MEASURED.with_borrow(|m| m.get(&key).copied()) {
            return Ok(size);
        }
        let saved = self.ctx.font();
        self.ctx.set_font(&key.0);
        let m = self.ctx.measure_text(text);
        self.ctx.set_font(&saved);
        let m = m.map_err(|e| {
            DrawingErrorKind::FontError(Box::new(std::io::Error::other(format!("{e:?}"))))
        })?;
        let height = m.font_bounding_box_ascent() + m.font_bounding_box_descent();
        let size = (m.width().round() as u32, height.round() as u32);
        MEASURED.with_borrow_mut(|cache| {
            if cache.len() >= MEASURED_MAX {
                cache.clear();
            }
            cache.insert(key, size);
        });
        Ok(size)
    }
}
