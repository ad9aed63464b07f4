//! The page's panels, built once at start: the controls (from
//! [`crate::controls`]), the toolbar (presets, reset, A/B, link) and every
//! view's export bar (from [`crate::views::VIEWS`]); and the controls'
//! values refreshed after a link, preset or reset.

use super::*;

pub(super) fn build_controls(page: &Shared) {
    let doc = page.borrow().doc.clone();
    let Some(panel) = doc.get_element_by_id("controls") else {
        return;
    };
    for group in Group::ALL {
        let Some(fs) = el(&doc, "fieldset") else {
            continue;
        };
        let container: Element = if group == Group::Advanced {
            let Some(det) = el(&doc, "details") else {
                continue;
            };
            det.set_class_name("advanced");
            if let Some(sum) = el(&doc, "summary") {
                sum.set_text_content(Some(group.title()));
                check(det.append_child(&sum));
            }
            check(det.append_child(&fs));
            check(panel.append_child(&det));
            fs
        } else {
            if let Some(lg) = el(&doc, "legend") {
                lg.set_text_content(Some(group.title()));
                check(fs.append_child(&lg));
            }
            check(panel.append_child(&fs));
            fs
        };
        for c in controls().into_iter().filter(|c| c.group == group) {
            let Some(div) = el(&doc, "div") else { continue };
            div.set_class_name("control");
            div.set_id(&format!("control-{}", c.key));
            check(div.set_attribute("title", &crate::words::tooltip(c.key, c.description)));
            check(div.set_attribute(
                "data-applies",
                match c.applies {
                    solver::keys::Applies::Both => "both",
                    solver::keys::Applies::Ravigneaux => "ravigneaux",
                    solver::keys::Applies::GearPair => "gear-pair",
                },
            ));
            let Some(label) = el(&doc, "label") else {
                continue;
            };
            label.set_text_content(Some(&c.label));
            check(div.append_child(&label));
            match &c.widget {
                Widget::Slider {
                    min,
                    max,
                    step,
                    field_min,
                    field_max,
                } => {
                    check(label.set_attribute("for", &format!("num-{}", c.key)));
                    let (Some(range), Some(num), Some(unit)) =
                        (el(&doc, "input"), el(&doc, "input"), el(&doc, "span"))
                    else {
                        continue;
                    };
                    let (Ok(range), Ok(num)) = (
                        range.dyn_into::<HtmlInputElement>(),
                        num.dyn_into::<HtmlInputElement>(),
                    ) else {
                        continue;
                    };
                    range.set_type("range");
                    range.set_id(&format!("slider-{}", c.key));
                    range.set_min(&min.to_string());
                    range.set_max(&max.to_string());
                    range.set_step(&step.to_string());
                    check(range.set_attribute("aria-label", &format!("{} slider", c.label)));
                    num.set_type("number");
                    num.set_id(&format!("num-{}", c.key));
                    num.set_min(&field_min.to_string());
                    num.set_max(&field_max.to_string());
                    num.set_step("any");
                    unit.set_class_name("unit");
                    unit.set_text_content(Some(&c.unit));
                    check(div.append_child(&range));
                    check(div.append_child(&num));
                    check(div.append_child(&unit));
                    let key = c.key.to_string();
                    let p2 = page.clone();
                    let num2 = num.clone();
                    listen(&range.clone().into(), "input", move |_e: Event| {
                        let v = range.value();
                        num2.set_value(&v);
                        queue_input(&p2, &key, &v);
                    });
                    let key = c.key.to_string();
                    let p2 = page.clone();
                    let num3 = num.clone();
                    listen(&num.into(), "change", move |_e: Event| {
                        queue_input(&p2, &key, &num3.value());
                    });
                }
                Widget::Select(options) => {
                    check(label.set_attribute("for", &format!("sel-{}", c.key)));
                    let Some(sel) =
                        el(&doc, "select").and_then(|s| s.dyn_into::<HtmlSelectElement>().ok())
                    else {
                        continue;
                    };
                    sel.set_id(&format!("sel-{}", c.key));
                    for (value, text) in options {
                        add_option(&doc, &sel, value, text);
                    }
                    check(div.append_child(&sel));
                    let key = c.key.to_string();
                    let p2 = page.clone();
                    let sel2 = sel.clone();
                    listen(&sel.into(), "change", move |_e: Event| {
                        queue_input(&p2, &key, &sel2.value());
                    });
                }
            }
            check(container.append_child(&div));
        }
    }
}

pub(super) fn add_option(doc: &Document, sel: &HtmlSelectElement, value: &str, text: &str) {
    if let Some(o) = el(doc, "option") {
        check(o.set_attribute("value", value));
        o.set_text_content(Some(text));
        check(sel.append_child(&o));
    }
}

pub(super) fn queue_input(page: &Shared, key: &str, value: &str) {
    {
        let mut p = page.borrow_mut();
        let t = now(&p.window);
        p.core.input(key, value, t);
    }
    request_frame(page);
}

pub(super) fn refresh_controls(p: &Shell) {
    let params = &p.core.ctl().settings().params;
    let model = params.kind();
    // The mesh list depends on the model.
    if let Some(sel) = by_id::<HtmlSelectElement>(&p.doc, "sel-mesh") {
        let names = p.core.ctl().mesh_names();
        let wanted: Vec<String> = names.iter().cloned().chain(["worst".to_string()]).collect();
        let current: Vec<String> = (0..sel.length())
            .filter_map(|i| sel.item(i))
            .filter_map(|o| o.get_attribute("value"))
            .collect();
        if current != wanted {
            sel.set_text_content(None);
            for n in &names {
                add_option(&p.doc, &sel, n, n);
            }
            add_option(&p.doc, &sel, "worst", "worst (largest dynamic factor)");
        }
    }
    for c in controls() {
        if let Some(div) = by_id::<HtmlElement>(&p.doc, &format!("control-{}", c.key)) {
            div.set_hidden(!shown_for(&c, model));
        }
        let text = match c.target {
            Target::Param => match solver::keys::get(params, c.key) {
                Some(solver::keys::Value::Num(x)) => field_text(x),
                Some(solver::keys::Value::Text(t)) => t,
                None => continue,
            },
            Target::View => match p.core.ctl().settings().view.get(c.key) {
                Some(t) => t,
                None => continue,
            },
        };
        match c.widget {
            Widget::Slider { .. } => {
                if let Some(n) = by_id::<HtmlInputElement>(&p.doc, &format!("num-{}", c.key)) {
                    n.set_value(&text);
                    n.set_placeholder(if text.is_empty() { "mixed" } else { "" });
                }
                if let Some(s) = by_id::<HtmlInputElement>(&p.doc, &format!("slider-{}", c.key)) {
                    if !text.is_empty() {
                        s.set_value(&text);
                    }
                }
            }
            Widget::Select(_) => {
                if let Some(s) = by_id::<HtmlSelectElement>(&p.doc, &format!("sel-{}", c.key)) {
                    s.set_value(&text);
                }
            }
        }
    }
}

pub(super) fn build_toolbar(page: &Shared) {
    let doc = page.borrow().doc.clone();
    if let Some(sel) = by_id::<HtmlSelectElement>(&doc, "preset") {
        add_option(&doc, &sel, "", "Choose a preset…");
        for p in PRESETS {
            add_option(&doc, &sel, p.id, p.title);
        }
        let page2 = page.clone();
        let sel2 = sel.clone();
        listen(&sel.into(), "change", move |_e: Event| {
            let id = sel2.value();
            if id.is_empty() {
                return;
            }
            let fx = {
                let mut p = page2.borrow_mut();
                let t = now(&p.window);
                p.core.ctl_mut().apply_preset(&id, t)
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
    if let Some(btn) = doc.get_element_by_id("reset") {
        let page2 = page.clone();
        listen(&btn.into(), "click", move |_e: Event| {
            let fx = {
                let mut p = page2.borrow_mut();
                let t = now(&p.window);
                p.core.ctl_mut().load_query("", t)
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
    for (id, pin) in [("pin-a", true), ("clear-a", false)] {
        if let Some(btn) = doc.get_element_by_id(id) {
            let page2 = page.clone();
            listen(&btn.into(), "click", move |_e: Event| {
                let fx = {
                    let mut p = page2.borrow_mut();
                    let t = now(&p.window);
                    if pin {
                        p.core.ctl_mut().pin_a(t)
                    } else {
                        p.core.ctl_mut().clear_a()
                    }
                };
                run_effects(&page2, fx);
                request_frame(&page2);
            });
        }
    }
    if let Some(btn) = doc.get_element_by_id("copy-link") {
        let page2 = page.clone();
        listen(&btn.into(), "click", move |_e: Event| copy_link(&page2));
    }
    if let Some(m) = doc.get_element_by_id("messages") {
        let page2 = page.clone();
        listen(&m.into(), "click", move |_e: Event| {
            page2.borrow_mut().core.ctl_mut().clear_issues();
            request_frame(&page2);
        });
    }
}

/// Shows `text` next to the Copy link button for about two seconds (the
/// status line is rewritten every frame, so it has its own element).
fn confirm(window: &web_sys::Window, doc: &web_sys::Document, text: &str) {
    let Some(e) = doc.get_element_by_id("copy-done") else {
        return;
    };
    e.set_text_content(Some(text));
    check(e.remove_attribute("hidden"));
    let stamp = format!("{}", js_sys::Date::now());
    check(e.set_attribute("data-shown", &stamp));
    let hide = Closure::<dyn FnMut()>::new(move || {
        // A later click restarts the two seconds: only its own timer hides it.
        if e.get_attribute("data-shown").as_deref() == Some(stamp.as_str()) {
            check(e.set_attribute("hidden", ""));
        }
    });
    check(
        window
            .set_timeout_with_callback_and_timeout_and_arguments_0(
                hide.as_ref().unchecked_ref(),
                2000,
            )
            .map(|_| ()),
    );
    hide.forget();
}

pub(super) fn copy_link(page: &Shared) {
    let (window, doc) = {
        let p = page.borrow();
        (p.window.clone(), p.doc.clone())
    };
    let href = window.location().href().unwrap_or_default();
    let clipboard = window.navigator().clipboard();
    let (ok_doc, ok_win) = (doc.clone(), window.clone());
    let ok = Closure::<dyn FnMut(JsValue)>::new(move |_v: JsValue| {
        confirm(&ok_win, &ok_doc, "Link copied to the clipboard.");
    });
    let (fail_doc, fail_win) = (doc.clone(), window.clone());
    let fail = Closure::<dyn FnMut(JsValue)>::new(move |_v: JsValue| {
        confirm(
            &fail_win,
            &fail_doc,
            "Could not copy; the link is in the address bar.",
        );
    });
    // The promise settles into `ok` or `fail`, which say so in the status
    // line; nothing else waits for it.
    drop(clipboard.write_text(&href).then2(&ok, &fail));
    // One pair per click; small and rare, so they are leaked rather than tracked.
    ok.forget();
    fail.forget();
    if let Some(b) = doc.get_element_by_id("copy-link") {
        check(b.set_attribute("data-link", &href));
    }
}

pub(super) fn download_text(doc: &Document, name: &str, mime: &str, text: &str) {
    let parts = js_sys::Array::of1(&JsValue::from_str(text));
    let opts = BlobPropertyBag::new();
    opts.set_type(mime);
    let Ok(blob) = Blob::new_with_str_sequence_and_options(&parts, &opts) else {
        return;
    };
    let Ok(url) = Url::create_object_url_with_blob(&blob) else {
        return;
    };
    download_url(doc, name, &url);
}

pub(super) fn download_url(doc: &Document, name: &str, url: &str) {
    let Some(a) = el(doc, "a").and_then(|a| a.dyn_into::<HtmlAnchorElement>().ok()) else {
        return;
    };
    a.set_href(url);
    a.set_download(name);
    a.click();
}

/// Saves a view as a PNG at twice its size: its SVG picture (the same
/// drawing) rasterized onto an offscreen canvas of twice the canvas's size;
/// the canvas itself if the picture cannot be drawn.
fn png_2x(page: &Shared, v: ViewId) {
    let (doc, svg) = {
        let p = page.borrow();
        (p.doc.clone(), p.core.ctl().plot_svg(v))
    };
    let (w, h) = page.borrow().core.ctl().canvas_size(v);
    let name = format!("gearshock-{}.png", v.key());
    let (Ok(svg), Ok(img)) = (svg, web_sys::HtmlImageElement::new()) else {
        if let Some(url) = canvas(&doc, v).and_then(|cv| cv.to_data_url().ok()) {
            download_url(&doc, &name, &url);
        }
        return;
    };
    let src = format!(
        "data:image/svg+xml;charset=utf-8,{}",
        String::from(js_sys::encode_uri_component(&svg))
    );
    let img2 = img.clone();
    let onload = Closure::<dyn FnMut()>::new(move || {
        let Some(cv) = doc
            .create_element("canvas")
            .ok()
            .and_then(|e| e.dyn_into::<HtmlCanvasElement>().ok())
        else {
            return;
        };
        cv.set_width(2 * w);
        cv.set_height(2 * h);
        if let Some(ctx) = ctx2d(&cv) {
            check(ctx.draw_image_with_html_image_element_and_dw_and_dh(
                &img2,
                0.0,
                0.0,
                f64::from(2 * w),
                f64::from(2 * h),
            ));
        }
        if let Ok(url) = cv.to_data_url() {
            download_url(&doc, &name, &url);
        }
    });
    img.set_onload(Some(onload.as_ref().unchecked_ref()));
    // One per click, small: leaked rather than tracked.
    onload.forget();
    img.set_src(&src);
}

/// A button added to `parent` that calls `on_click`.
pub(super) fn add_button(
    page: &Shared,
    parent: &Element,
    text: &str,
    title: &str,
    on_click: impl FnMut(Event) + 'static,
) {
    let doc = page.borrow().doc.clone();
    let Some(b) = el(&doc, "button") else {
        return;
    };
    check(b.set_attribute("type", "button"));
    check(b.set_attribute("title", title));
    check(b.set_attribute("aria-label", title));
    b.set_text_content(Some(text));
    check(parent.append_child(&b));
    listen(&b.into(), "click", on_click);
}

pub(super) fn build_exports(page: &Shared) {
    let doc = page.borrow().doc.clone();
    for v in ViewId::ALL {
        let Some(bar) = doc.get_element_by_id(&format!("exports-{}", v.key())) else {
            continue;
        };
        let page2 = page.clone();
        let png = v.export_name("a PNG image at twice the size");
        add_button(page, &bar, "PNG", &png, move |_| png_2x(&page2, v));
        let page2 = page.clone();
        add_button(
            page,
            &bar,
            "SVG",
            &v.export_name("an SVG picture"),
            move |_| {
                let r = page2.borrow().core.ctl().export_svg(v);
                match r {
                    Ok(e) => run_effects(&page2, vec![e]),
                    Err(e) => set_text(&page2.borrow().doc, "status", &e.to_string()),
                }
            },
        );
        for fmt in Format::ALL {
            let title = v.export_name(fmt.label());
            let page2 = page.clone();
            add_button(page, &bar, fmt.label(), &title, move |_| {
                let r = page2.borrow().core.ctl().export(v, fmt);
                finish_export(&page2, r.map(|e| vec![e]));
            });
        }
        if v.cli_export_title().is_some() {
            let page2 = page.clone();
            let title = v.export_name("JSON for the command-line tool");
            add_button(page, &bar, "CLI JSON", &title, move |_| {
                let r = page2.borrow_mut().core.ctl_mut().export_cli(v);
                finish_export(&page2, r);
            });
        }
    }
    if let Some(sec) = doc.get_element_by_id("export-cli") {
        let page2 = page.clone();
        let text = "Download gearshock-params.json";
        add_button(
            page,
            &sec,
            text,
            "Download the parameters as JSON for the command-line tool",
            move |_| {
                let fx = vec![page2.borrow().core.ctl().export_params()];
                run_effects(&page2, fx);
            },
        );
    }
}

/// Offers an export's file, or says in the status line why there is none.
pub(super) fn finish_export(page: &Shared, r: Result<Vec<Effect>, ExportError>) {
    match r {
        Ok(fx) => run_effects(page, fx),
        Err(e) => set_text(&page.borrow().doc, "status", &e.to_string()),
    }
}
