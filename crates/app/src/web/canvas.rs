//! The plotters backend of the page's canvases: `plotters-canvas`'s
//! `CanvasBackend` for every drawing call, but text measured with the
//! canvas's own `measureText`. On wasm32 plotters measures a label by
//! adding a span to the page and reading its size, a forced layout of the
//! whole page per label: some 300 per page load, up to 36 ms each, all on
//! the main thread.

use figures::plots::css;
use figures::plots::decimate::long_path;
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

/// A canvas backend whose text sizes come from `measureText`.
pub(super) struct Canvas {
    inner: CanvasBackend,
    ctx: CanvasRenderingContext2d,
    /// The drawing's size, where it is not the canvas's (present mode).
    size: Option<(u32, u32)>,
    /// Filled opaque circles waiting to be filled as one path, and their
    /// colour ([`Canvas::flush`]).
    dots: Vec<(BackendCoord, u32)>,
    dots_color: Option<BackendColor>,
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
            dots: Vec::new(),
            dots_color: None,
        })
    }

    /// Fills the waiting circles: one path of all of them and one fill.
    /// plotters-canvas sets the colour, begins a path, draws an arc and
    /// fills per circle (four calls into JavaScript): a family's six
    /// Poincaré sections of 1000 periods were 6 000 fills. Opaque circles
    /// filled together cover the same pixels as one by one. Every other
    /// drawing call flushes first, so the order of what is drawn is kept.
    fn flush(&mut self) -> Result<(), Error> {
        let Some(color) = self.dots_color else {
            return Ok(());
        };
        if self.dots.is_empty() {
            return Ok(());
        }
        self.ctx.set_fill_style_str(&css::color(color));
        let dots = std::mem::take(&mut self.dots);
        // One path string of the circles, two arcs each, parsed once.
        let mut d = String::with_capacity(40 * dots.len());
        for &((x, y), r) in &dots {
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
        for &(center, r) in &dots {
            self.inner.draw_circle(center, r, &color, true)?;
        }
        Ok(())
    }
}

/// Circles still waiting when a drawing ends without `present` are filled.
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
        self.flush()?;
        self.inner.draw_line(from, to, style)
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
        self.flush()?;
        let pts: Vec<BackendCoord> = path.into_iter().collect();
        let Some(Ok(p2d)) = long_path(&pts).map(|d| Path2d::new_with_path_string(&d)) else {
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
        let same = self
            .dots_color
            .is_some_and(|c| c.rgb == color.rgb && c.alpha == color.alpha);
        if !same {
            self.flush()?;
            self.dots_color = Some(color);
        }
        self.dots.push((center, radius));
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
