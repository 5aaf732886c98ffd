//! The page's frame: escaping, images as data URIs, and the inline style.

use base64::Engine as _;

/// `text` safe in HTML text and in a quoted attribute.
pub(super) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// An image as a `data:image/png;base64,…` URI.
pub(super) fn png_data_uri<P, C>(image: &image::ImageBuffer<P, C>) -> String
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let mut png = std::io::Cursor::new(Vec::new());
    let _ = image.write_to(&mut png, image::ImageFormat::Png);
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png.into_inner())
    )
}

/// An id for a group of an asset's findings, unique on the page.
pub(super) fn anchor_of(uri: &str, group: &str) -> String {
    let safe = |s: &str| -> String {
        s.chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
            .collect()
    };
    format!("{}--{}", safe(uri), safe(group))
}

/// The whole page around `body`.
pub(super) fn document(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>{}</title><style>{STYLE}</style></head><body>{body}<footer>Made by gltfmat {}.</footer></body></html>\n",
        escape(title),
        env!("CARGO_PKG_VERSION")
    )
}

const STYLE: &str = "
body{font:15px/1.45 system-ui,sans-serif;margin:2em auto;max-width:72em;padding:0 1em;color:#1d1d1f;background:#fff}
h1{font-size:1.6em}h2{font-size:1.25em;border-top:1px solid #ccc;padding-top:.8em;word-break:break-all}
h3{font-size:1.05em}h4{font-size:.95em;margin:.8em 0 .2em;font-family:ui-monospace,monospace}
table.summary{border-collapse:collapse;width:100%}
table.summary th,table.summary td{border-bottom:1px solid #ddd;padding:.25em .5em;text-align:right}
table.summary th:first-child,table.summary td:first-child{text-align:left;word-break:break-all}
tr.bad td:nth-child(2){color:#b00020;font-weight:600}
.failure{color:#b00020}
ul.findings{list-style:none;padding-left:0;margin:0}
ul.findings li{padding:.15em 0;border-bottom:1px dotted #e5e5e5}
.sev{display:inline-block;min-width:4.5em;font-weight:600}
li.error .sev{color:#b00020}li.warning .sev{color:#8a5a00}li.info .sev,li.hint .sev{color:#555}
.code{font-family:ui-monospace,monospace;font-size:.9em}
.where{color:#555;font-family:ui-monospace,monospace;font-size:.85em;word-break:break-all}
.material{display:flex;gap:1em;align-items:flex-start;border:1px solid #ddd;border-radius:6px;padding:.6em;margin:.6em 0}
.material table{border-collapse:collapse;font-size:.9em}
.material td,.material th{padding:.15em .4em;text-align:left;vertical-align:top;border-bottom:1px solid #eee}
.row{display:flex;gap:1em;flex-wrap:wrap}
figure{margin:0;text-align:center;font-size:.85em;max-width:12em}
img{background:repeating-conic-gradient(#ddd 0 25%,#fff 0 50%) 0 0/12px 12px;border:1px solid #ccc}
img.pixelated{image-rendering:pixelated}
.pair.different h3,.pair.not-evaluated h3{color:#b00020}.pair.same h3{color:#0a6b2c}
dl dt{font-family:ui-monospace,monospace;font-weight:600;margin-top:.6em}
pre{white-space:pre-wrap;font-size:.85em;background:#f6f6f6;padding:.5em}
footer{margin-top:3em;color:#777;font-size:.85em}
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_in_a_message_is_text_not_markup() {
        assert_eq!(
            escape("<img src=x onerror=\"a\">&'"),
            "&lt;img src=x onerror=&quot;a&quot;&gt;&amp;&#39;"
        );
    }
}
