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

/// A canvas backend whose text sizes come from `measureText`.
pub(super) struct Canvas {
    inner: CanvasBackend,
    ctx: CanvasRenderingContext2d,
    /// The drawing's size, where it is not the canvas's (present mode).
    size: Option<(u32, u32)>,
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
        Some(Self { inner, ctx, size })
    }
}

impl DrawingBackend for Canvas {
    type ErrorType = <CanvasBackend as DrawingBackend>::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.size.unwrap_or_else(|| self.inner.get_size())
    }

    fn ensure_prepared(&mut self) -> Result<(), Error> {
        self.inner.ensure_prepared()
    }

    fn present(&mut self) -> Result<(), Error> {
        self.inner.present()
    }

    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Result<(), Error> {
        self.inner.draw_pixel(point, color)
    }

    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), Error> {
        self.inner.draw_line(from, to, style)
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), Error> {
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
        self.inner.draw_circle(center, radius, style, fill)
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), Error> {
        self.inner.fill_polygon(vert, style)
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), Error> {
        self.inner.draw_text(text, style, pos)
    }

    /// The text's advance width and its font's line height (ascent plus
    /// descent, what a span of it measures), in the font `draw_text` sets.
    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), Error> {
        let saved = self.ctx.font();
        self.ctx.set_font(&css::font(style));
        let m = self.ctx.measure_text(text);
        self.ctx.set_font(&saved);
        let m = m.map_err(|e| {
            DrawingErrorKind::FontError(Box::new(std::io::Error::other(format!("{e:?}"))))
        })?;
        let height = m.font_bounding_box_ascent() + m.font_bounding_box_descent();
        Ok((m.width().round() as u32, height.round() as u32))
    }
}
