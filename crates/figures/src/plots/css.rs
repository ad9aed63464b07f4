//! Plotters' styles as the canvas's CSS strings, for the page's canvas
//! backend (`web/canvas.rs`), which strokes long paths and measures text
//! itself: the color it strokes with and the font it measures in, the
//! same font plotters-canvas sets when it draws the text.

use plotters_backend::{BackendColor, BackendTextStyle};

/// A color as CSS: `rgba(r,g,b,a)`.
pub fn color(c: BackendColor) -> String {
    let (r, g, b) = c.rgb;
    format!("rgba({r},{g},{b},{})", c.alpha)
}

/// A text style's CSS font: `style sizepx family`.
pub fn font<S: BackendTextStyle>(style: &S) -> String {
    format!(
        "{} {}px {}",
        style.style().as_str(),
        style.size(),
        style.family().as_str()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::style::{FontStyle, IntoFont, TextStyle};

    #[test]
    fn a_color_and_a_font_read_as_css() {
        let c = BackendColor {
            alpha: 0.5,
            rgb: (10, 20, 250),
        };
        assert_eq!(color(c), "rgba(10,20,250,0.5)");
        let f = TextStyle::from(("sans-serif", 13).into_font().style(FontStyle::Bold));
        assert_eq!(font(&f), "bold 13px sans-serif");
        let g = TextStyle::from(("serif", 9.5).into_font());
        assert_eq!(font(&g), "normal 9.5px serif");
    }
}
