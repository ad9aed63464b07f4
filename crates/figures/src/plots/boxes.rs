//! The boxes of the text a plot draws: a plotters backend that passes every
//! call to the backend it wraps and notes, for each text, the box it covers
//! on the canvas (from the wrapped backend's own measure, the anchor and
//! the rotation plotters asked for). The page reports them in its status,
//! and a browser test checks that no two overlap and none leaves its canvas.

use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
    FontTransform,
};
use std::cell::RefCell;
use std::rc::Rc;

/// One drawn text: its box in canvas pixels (left, top, right, bottom) and
/// the text.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TextBox {
    /// Left, top, right and bottom edges in canvas pixels.
    pub edges: [i32; 4],
    /// What was drawn.
    pub text: String,
}

impl TextBox {
    /// Whether the two boxes share more than a line of pixels: touching
    /// edges do not count.
    pub fn overlaps(&self, other: &TextBox) -> bool {
        let [l1, t1, r1, b1] = self.edges;
        let [l2, t2, r2, b2] = other.edges;
        l1.max(l2) < r1.min(r2) && t1.max(t2) < b1.min(b2)
    }
}

/// The box text of `(w, h)` pixels covers when drawn at `pos` with this
/// anchor and rotation (the canvas backend rotates about `pos`).
pub fn text_box(
    pos: BackendCoord,
    (w, h): (u32, u32),
    h_pos: HPos,
    v_pos: VPos,
    rot: &FontTransform,
) -> [i32; 4] {
    let (w, h) = (w as i32, h as i32);
    let x0 = match h_pos {
        HPos::Left => 0,
        HPos::Center => -w / 2,
        HPos::Right => -w,
    };
    let y0 = match v_pos {
        VPos::Top => 0,
        VPos::Center => -h / 2,
        VPos::Bottom => -h,
    };
    let (x1, y1) = (x0 + w, y0 + h);
    // Corners in the text's own frame, turned as the canvas turns them.
    let turn = |(x, y): (i32, i32)| match rot {
        FontTransform::None => (x, y),
        FontTransform::Rotate90 => (-y, x),
        FontTransform::Rotate180 => (-x, -y),
        FontTransform::Rotate270 => (y, -x),
    };
    let (a, b) = (turn((x0, y0)), turn((x1, y1)));
    [
        pos.0 + a.0.min(b.0),
        pos.1 + a.1.min(b.1),
        pos.0 + a.0.max(b.0),
        pos.1 + a.1.max(b.1),
    ]
}

/// A backend that draws with `B` and notes every text's box.
pub struct Boxed<B> {
    inner: B,
    boxes: Rc<RefCell<Vec<TextBox>>>,
}

impl<B> Boxed<B> {
    /// `inner`, noting text boxes in `boxes`.
    pub fn new(inner: B, boxes: Rc<RefCell<Vec<TextBox>>>) -> Self {
        Boxed { inner, boxes }
    }
}

type Error<B> = DrawingErrorKind<<B as DrawingBackend>::ErrorType>;

impl<B: DrawingBackend> DrawingBackend for Boxed<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), Error<B>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), Error<B>> {
        self.inner.present()
    }
    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Result<(), Error<B>> {
        self.inner.draw_pixel(point, color)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), Error<B>> {
        self.inner.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), Error<B>> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), Error<B>> {
        self.inner.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), Error<B>> {
        self.inner.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), Error<B>> {
        self.inner.fill_polygon(vert, style)
    }
    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), Error<B>> {
        if style.color().alpha > 0.0 && !text.trim().is_empty() {
            let size = self.inner.estimate_text_size(text, style)?;
            let a = style.anchor();
            self.boxes.borrow_mut().push(TextBox {
                edges: text_box(pos, size, a.h_pos, a.v_pos, &style.transform()),
                text: text.to_string(),
            });
        }
        self.inner.draw_text(text, style, pos)
    }
    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), Error<B>> {
        self.inner.estimate_text_size(text, style)
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), Error<B>> {
        self.inner.blit_bitmap(pos, size, src)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_follows_the_anchor_and_the_rotation() {
        // Centred on (100, 50): 40 wide, 10 high.
        let b = text_box(
            (100, 50),
            (40, 10),
            HPos::Center,
            VPos::Center,
            &FontTransform::None,
        );
        assert_eq!(b, [80, 45, 120, 55]);
        // A y-axis description, turned a quarter anticlockwise about its
        // anchor, stands 40 high and 10 wide.
        let b = text_box(
            (20, 200),
            (40, 10),
            HPos::Center,
            VPos::Top,
            &FontTransform::Rotate270,
        );
        assert_eq!(b, [20, 180, 30, 220]);
        let right = text_box(
            (100, 0),
            (30, 12),
            HPos::Right,
            VPos::Top,
            &FontTransform::None,
        );
        assert_eq!(right, [70, 0, 100, 12]);
    }

    #[test]
    fn touching_boxes_do_not_overlap_and_sharing_ones_do() {
        let a = TextBox {
            edges: [0, 0, 10, 10],
            text: "a".into(),
        };
        let b = TextBox {
            edges: [10, 0, 20, 10],
            text: "b".into(),
        };
        let c = TextBox {
            edges: [9, 9, 20, 20],
            text: "c".into(),
        };
        assert!(!a.overlaps(&b));
        assert!(a.overlaps(&c));
        assert!(b.overlaps(&c));
    }
}
