//! The page in a real browser: headless Chromium, driven over WebDriver (chromedriver),
//! uploads the sample part and a box without its top, and the test reads the page:
//! the volume shown is the command's (`meshvol volume --json`), so are the verdict
//! (`check --json`) and the warnings, the view is drawn (the canvas is not blank) and
//! the hole's rim is drawn in its colour on the broken box. The same for the page
//! `check --html` writes, opened from its file. Screenshots are kept under
//! target/tmp/serve-screenshots/. Skipped, saying why, without chromium and
//! chromedriver (Debian's `chromium` and `chromium-driver`; .ci/run installs them).

mod common;

use common::server::{agent, Server};
use common::{box_obj, meshvol, p, write};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

fn found(names: &[&str]) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    names.iter().find_map(|n| std::env::split_paths(&path).map(|d| d.join(n)).find(|p| p.is_file()))
}

/// chromedriver, stopped when dropped, and one browser session on it.
struct Browser {
    driver: Child,
    url: String,
    session: String,
}

impl Browser {
    fn start(chromium: &Path, chromedriver: &Path) -> Browser {
        let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
        let driver = Command::new(chromedriver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts");
        let url = format!("http://127.0.0.1:{port}");
        let mut browser = Browser { driver, url, session: String::new() };
        // chromedriver takes a moment to listen: ask until it answers (at most a minute).
        let ready = (0..600).any(|_| {
            let up = agent().get(format!("{}/status", browser.url)).call().is_ok();
            if !up {
                std::thread::sleep(Duration::from_millis(100));
            }
            up
        });
        assert!(ready, "chromedriver does not answer");
        let capabilities = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {
                "binary": chromium.to_str().unwrap(),
                "args": ["--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                         "--window-size=1280,900", "--use-angle=swiftshader",
                         "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist"]
            }
        }}});
        let answer = browser.call("POST", "/session", capabilities);
        browser.session = answer["sessionId"].as_str().expect("a session").to_string();
        browser
    }

    /// A WebDriver command: its `value`, or a panic with the driver's message.
    fn call(&self, method: &str, path: &str, body: Value) -> Value {
        let url = format!("{}{path}", self.url);
        let agent = agent();
        let mut response = match method {
            "GET" => agent.get(&url).call(),
            "DELETE" => agent.delete(&url).call(),
            _ => agent.post(&url).send_json(body),
        }
        .expect("chromedriver answers");
        let text = response.body_mut().read_to_string().unwrap();
        let value: Value = serde_json::from_str(&text).unwrap();
        if response.status().as_u16() != 200 {
            panic!("WebDriver {method} {path}: {text}");
        }
        value["value"].clone()
    }

    fn session_call(&self, method: &str, path: &str, body: Value) -> Value {
        self.call(method, &format!("/session/{}{path}", self.session), body)
    }

    fn open(&self, url: &str) {
        self.session_call("POST", "/url", json!({ "url": url }));
    }

    /// Runs `script` (a function body) in the page: what it returns.
    fn run(&self, script: &str) -> Value {
        self.session_call("POST", "/execute/sync", json!({ "script": script, "args": [] }))
    }

    /// Waits (at most two minutes) until `script` returns something other than null.
    fn until(&self, script: &str) -> Value {
        for _ in 0..1200 {
            let v = self.run(script);
            if !v.is_null() {
                return v;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        panic!("the page never got there: {script}");
    }

    /// Chooses `file` in the page's file input.
    fn upload(&self, file: &Path) {
        let element = self.session_call(
            "POST",
            "/element",
            json!({ "using": "css selector", "value": "#files" }),
        );
        let id =
            element.as_object().unwrap().values().next().unwrap().as_str().unwrap().to_string();
        self.session_call("POST", &format!("/element/{id}/value"), json!({ "text": p(file) }));
    }

    /// Saves a screenshot of the page to `path` (PNG).
    fn screenshot(&self, path: &Path) {
        let encoded = self.session_call("GET", "/screenshot", Value::Null);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, base64(encoded.as_str().unwrap())).unwrap();
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let _ = agent().delete(format!("{}/session/{}", self.url, self.session)).call();
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

/// Standard base64 decoded (the screenshot).
fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let clean: Vec<u8> = text.bytes().filter(|c| !matches!(c, b'=' | b'\n' | b'\r')).collect();
    let mut out = Vec::with_capacity(clean.len() * 3 / 4);
    for chunk in clean.chunks(4) {
        let n =
            chunk.iter().enumerate().fold(0u32, |n, (i, &c)| n | (value(c) as u32) << (18 - 6 * i));
        out.extend(&n.to_be_bytes()[1..chunk.len()]);
    }
    out
}

/// What the card of `name` shows, once measured: its state, verdict, volume (the
/// number behind the text, and the text), warnings, and the view's pixels (how many
/// are not the white background, and how many are the hole's red).
const CARD: &str = r#"
const card = [...document.querySelectorAll('.card')].find(c => c.dataset.file === NAME);
if (!card || !card.dataset.state) return null;
const view = document.getElementById('view');
if (card.dataset.state === 'done' && view.dataset.drawn !== 'true') return null;
const canvas = view.querySelector('canvas');
let painted = 0, red = 0;
if (canvas) {
  const c2 = document.createElement('canvas');
  c2.width = canvas.width; c2.height = canvas.height;
  const g = c2.getContext('2d');
  g.drawImage(canvas, 0, 0);
  const d = g.getImageData(0, 0, c2.width, c2.height).data;
  for (let i = 0; i < d.length; i += 4) {
    if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) painted++;
    if (d[i] > 200 && d[i + 1] < 90 && d[i + 2] < 90) red++;
  }
}
const volume = card.querySelector('.volume');
return {
  state: card.dataset.state,
  verdict: (card.querySelector('.verdict') || {}).textContent,
  volume: volume ? volume.dataset.value : null,
  volume_text: volume ? volume.textContent : null,
  warnings: [...card.querySelectorAll('ul.warnings li')].map(li => li.textContent),
  problems: [...card.querySelectorAll('ul.problems li')].map(li => li.dataset.kind),
  error: (card.querySelector('.error') || {}).textContent || null,
  profile_shown: !document.getElementById('profile').hidden,
  section_at: document.getElementById('section-at').textContent,
  painted, red,
};
"#;

/// Moves the clip slider to VALUE (of 0..1000) as a hand would (an `input` event), then
/// reads what the page shows of the section and the grid slice: the label's text and
/// level, the picture's layer and caption, how many pixels are painted (neither the
/// canvas's grey nor white), and the colour at the centre of each cell (i major, j
/// minor) where the page placed the cells.
const SLIDER: &str = r#"
const clip = document.getElementById('clip');
clip.value = VALUE;
clip.dispatchEvent(new Event('input'));
const label = document.getElementById('cut-at'), canvas = document.getElementById('grid-slice');
const d = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
let painted = 0;
for (let i = 0; i < d.length; i += 4) {
  const grey = d[i] === 242 && d[i + 1] === 244 && d[i + 2] === 247;
  if (!grey && !(d[i] > 250 && d[i + 1] > 250 && d[i + 2] > 250)) painted++;
}
const caption = document.getElementById('slice-caption').textContent;
const [nx, ny] = caption.match(/grid (\d+) × (\d+)/).slice(1).map(Number);
const c = JSON.parse(canvas.dataset.cells), centres = [];
for (let i = 0; i < nx; i++) for (let j = 0; j < ny; j++) {
  const x = Math.floor(c.x0 + (i + 0.5) * c.sx), y = Math.floor(c.y0 - (j + 0.5) * c.sy);
  const k = 4 * (y * canvas.width + x);
  centres.push([d[k], d[k + 1], d[k + 2]]);
}
return { text: label.textContent, z: label.dataset.z, level: label.dataset.level,
         profile: document.getElementById('section-at').textContent,
         layer: canvas.dataset.layer, caption, painted, nx, ny, centres,
         shown: !document.getElementById('slices').hidden };
"#;

/// The number after `word ` in `text`.
fn number_after(text: &str, word: &str) -> f64 {
    let rest = text.split(&format!("{word} ")).nth(1).unwrap_or_else(|| panic!("{word}: {text}"));
    rest.split([' ', ',', ':'])
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|e| panic!("{word}: {e}: {text}"))
}

/// Moves the slider to three heights on the page showing `file` and checks each time that
/// the area and perimeter shown are `meshvol section --plane z=H --json`'s at the level
/// shown (to the 8 digits shown), that the profile's label beside it names the same
/// level with `meshvol below`'s volume there (to its 6 digits), that the picture is of the layer holding that level,
/// cell by cell as `meshvol grid --cells ... --fraction` gives the layer (every cell
/// wholly inside the part blue, every cell wholly outside white), and that it changes
/// from one height to the next.
fn assert_slices_agree(browser: &Browser, file: &Path, shots: &Path, shot: &str) {
    let work = tempfile::tempdir().unwrap();
    let mut pictures = Vec::new();
    // Levels 12, 31 and 32 (of 64): the top of the flange, the tube, and its narrower
    // band, each unlike the layer above or below it, so a picture of the wrong layer
    // or a section of the wrong level shows.
    for value in [195, 490, 505] {
        let shown = browser.run(&SLIDER.replace("VALUE", &value.to_string()));
        assert_eq!(shown["shown"], true, "{shown}");
        let text = shown["text"].as_str().unwrap();
        let z = shown["z"].as_str().unwrap();
        let section = cli_json(&["section", p(file), "--json", "--plane", &format!("z={z}")]);
        for key in ["area", "perimeter"] {
            let (on_page, cli) = (number_after(text, key), section[key].as_f64().unwrap());
            assert!((on_page - cli).abs() <= 5e-8 * cli.abs(), "{key}: {text} vs {cli}");
        }
        // The profile's label is at the same level: `meshvol below`'s volume there.
        let profile = shown["profile"].as_str().unwrap();
        let below = cli_json(&["below", p(file), "--json", "--plane", &format!("0,0,1,{z}")]);
        let (on_page, cli) = (number_after(profile, "below"), below["volume"].as_f64().unwrap());
        assert!((on_page - cli).abs() <= 5e-6 * cli.abs(), "{profile} vs {cli}");
        let zs = [profile, text].map(|t| number_after(t, "="));
        assert_eq!(zs[0], zs[1], "the two labels name one level: {profile} | {text}");
        let level: usize = shown["level"].as_str().unwrap().parse().unwrap();
        assert!(text.contains(&format!("(level {} of 64)", level + 1)), "{text}");
        let (nx, ny) =
            (shown["nx"].as_u64().unwrap() as usize, shown["ny"].as_u64().unwrap() as usize);
        let npy = work.path().join("cells.npy");
        let cells = format!("{nx},{ny},64");
        let grid = cli_json(&[
            "grid",
            p(file),
            "--json",
            "--cells",
            &cells,
            "--fraction",
            "--out",
            p(&npy),
        ]);
        let (z0, h) =
            (grid["bounds"]["min"][2].as_f64().unwrap(), grid["cell_size"][2].as_f64().unwrap());
        let z: f64 = z.parse().unwrap();
        let layer = ((z - z0) / h).floor() as usize;
        assert_eq!(shown["layer"], layer.to_string(), "{shown}");
        assert!(
            shown["caption"].as_str().unwrap().contains(&format!("layer k = {layer}:")),
            "{shown}"
        );
        let (_, fractions) = common::read_npy(&npy);
        let (mut full, mut empty) = (0, 0);
        for i in 0..nx {
            for j in 0..ny {
                let fraction = fractions[(i * ny + j) * 64 + layer];
                let colour: Vec<i64> = shown["centres"][i * ny + j]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_i64().unwrap())
                    .collect();
                let want = if fraction == 1.0 {
                    [24, 64, 160]
                } else if fraction == 0.0 {
                    [255, 255, 255]
                } else {
                    continue;
                };
                full += usize::from(fraction == 1.0);
                empty += usize::from(fraction == 0.0);
                let near = colour.iter().zip(want).all(|(c, w)| (c - w).abs() <= 2);
                assert!(
                    near,
                    "cell {i},{j} of layer {layer}: fraction {fraction}, colour {colour:?}"
                );
            }
        }
        assert!(full > 50 && empty > 50, "{full} full, {empty} empty cells");
        assert!(
            shown["painted"].as_u64().unwrap() > 2000,
            "the picture is drawn: {}",
            shown["painted"]
        );
        browser.screenshot(&shots.join(format!("{shot}-{value}.png")));
        pictures.push(shown["centres"].clone());
    }
    assert_ne!(pictures[0], pictures[1], "the picture changes with the level");
    assert_ne!(pictures[1], pictures[2], "the picture changes with the level");
}

fn card(browser: &Browser, name: &str) -> Value {
    browser.until(&CARD.replace("NAME", &serde_json::to_string(name).unwrap()))
}

fn cli_json(args: &[&str]) -> Value {
    let out = meshvol(args);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The page's card agrees with the command on `file`.
fn assert_agrees(shown: &Value, file: &Path, hole: bool) {
    let volume = cli_json(&["volume", "--json", p(file)]);
    let check = cli_json(&["check", "--json", p(file)]);
    assert_eq!(shown["state"], "done", "{shown}");
    let shown_volume: f64 = shown["volume"].as_str().unwrap().parse().unwrap();
    assert_eq!(shown_volume, volume["volume"].as_f64().unwrap(), "{shown}");
    // The text says the same number to the digits shown (8).
    let text: f64 =
        shown["volume_text"].as_str().unwrap().split(' ').next().unwrap().parse().unwrap();
    assert!((text - shown_volume).abs() <= 1e-7 * shown_volume.abs(), "{shown}");
    assert_eq!(shown["verdict"], check["verdict"], "{shown}");
    assert_eq!(shown["warnings"], volume["warnings"], "{shown}");
    // The profile's chart and the section at the slider's level (the top: all the volume).
    assert_eq!(shown["profile_shown"], true, "{shown}");
    assert!(shown["section_at"].as_str().unwrap().ends_with("(100 %)"), "{shown}");
    // The view is drawn: a good part of the canvas is not background.
    assert!(shown["painted"].as_u64().unwrap() > 2000, "{shown}");
    if hole {
        assert!(shown["red"].as_u64().unwrap() > 20, "the hole's rim is drawn: {shown}");
        assert!(shown["problems"].as_array().unwrap().contains(&json!("hole")), "{shown}");
    } else {
        assert_eq!(shown["red"], 0, "{shown}");
    }
}

#[test]
fn the_page_shows_the_commands_numbers_and_draws_the_part_and_its_hole() {
    let (Some(chromium), Some(chromedriver)) =
        (found(&["chromium", "chromium-browser", "google-chrome"]), found(&["chromedriver"]))
    else {
        eprintln!("skipped: no chromium and chromedriver on PATH (apt-get install chromium chromium-driver)");
        return;
    };
    let shots = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("serve-screenshots");
    let server = Server::start(&[]);
    let browser = Browser::start(&chromium, &chromedriver);
    browser.open(&server.url);
    let part = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/flanged-bushing.stl");
    let part = part.canonicalize().unwrap();
    browser.upload(&part);
    let shown = card(&browser, "flanged-bushing.stl");
    browser.screenshot(&shots.join("part.png"));
    assert_agrees(&shown, &part, false);
    assert_slices_agree(&browser, &part, &shots, "part-slices");

    let dir = tempfile::tempdir().unwrap();
    let open =
        write(dir.path(), "open-box.obj", box_obj([0.0; 3], [10.0, 20.0, 5.0], 1, true, true));
    browser.upload(&open);
    let shown = card(&browser, "open-box.obj");
    browser.screenshot(&shots.join("open-box.png"));
    assert_agrees(&shown, &open, true);

    // A file no reader takes: the reader's error on the page, and the server still up.
    let junk =
        write(dir.path(), "junk.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nope\n");
    browser.upload(&junk);
    let shown = card(&browser, "junk.stl");
    let expected = Command::new(common::bin())
        .current_dir(dir.path())
        .args(["check", "--json", "junk.stl"])
        .output()
        .unwrap();
    let expected: Value = serde_json::from_slice(&expected.stdout).unwrap();
    assert_eq!(shown["state"], "failed", "{shown}");
    assert_eq!(shown["error"], expected["error"], "{shown}");

    // Eight boxes each overlapping every other: 28 pairs, listed as the first five and a
    // count, the rest one click away.
    let mut boxes = String::new();
    for k in 0..8 {
        let lo = 0.1 * k as f64;
        boxes += &box_obj([lo; 3], [lo + 1.0; 3], 8 * k + 1, true, false);
    }
    let boxes = write(dir.path(), "boxes.obj", boxes);
    browser.upload(&boxes);
    let shown = card(&browser, "boxes.obj");
    assert_eq!(shown["state"], "done", "{shown}");
    let overlaps = |browser: &Browser| {
        browser.run(
            "return [...document.querySelectorAll('.card[data-file=\"boxes.obj\"] \
             li[data-kind=\"overlap\"]')].length;",
        )
    };
    assert_eq!(overlaps(&browser), 5);
    let more = browser.run(
        "const m = document.querySelector('.card[data-file=\"boxes.obj\"] \
         li[data-more=\"overlapping pairs\"]'); if (!m) return null; \
         const text = m.textContent; m.click(); return text;",
    );
    assert!(more.as_str().unwrap().contains("23 more overlapping pairs (28 in all)"), "{more}");
    assert_eq!(overlaps(&browser), 28);

    // A material with a file that declares no unit: the card asks for it, and measured in
    // the unit chosen, the mass is the command's.
    browser.run(
        "const m = document.getElementById('material'); m.value = '7.85g/cm3'; \
         m.dispatchEvent(new Event('change')); return true;",
    );
    let unitless =
        write(dir.path(), "unitless.obj", box_obj([0.0; 3], [10.0, 20.0, 5.0], 1, true, false));
    browser.upload(&unitless);
    let shown = card(&browser, "unitless.obj");
    assert_eq!(shown["state"], "asking", "{shown}");
    browser.run(
        "document.querySelector('.card[data-file=\"unitless.obj\"] button[data-unit=\"mm\"]').click(); \
         return true;",
    );
    let shown = card(&browser, "unitless.obj");
    assert_eq!(shown["state"], "done", "{shown}");
    let mass = browser.until(
        "const t = document.querySelector('.card[data-file=\"unitless.obj\"] .mass'); \
         return t ? t.dataset.value : null;",
    );
    let expected =
        cli_json(&["volume", "--json", p(&unitless), "--units", "mm", "--density", "7.85g/cm3"]);
    let mass: f64 = mass.as_str().unwrap().parse().unwrap();
    assert_eq!(mass, expected["mass"].as_f64().unwrap());
    // 1000 mm³ of steel at 7.85 g/cm³: 7.85 g.
    assert!((mass - 7.85).abs() < 1e-12, "{mass}");
    browser.run(
        "const m = document.getElementById('material'); m.value = ''; \
         document.getElementById('density').value = ''; return true;",
    );

    // `check --html`: the same page from one file, no server.
    let html = dir.path().join("open-box.html");
    let out = meshvol(&["check", p(&open), "--html", p(&html)]);
    assert_eq!(out.status.code(), Some(1), "an open box does not bound a volume");
    browser.open(&format!("file://{}", p(&html)));
    let name = p(&open).to_string();
    let shown = card(&browser, &name);
    browser.screenshot(&shots.join("open-box-html.png"));
    assert_agrees(&shown, &open, true);

    // The sample part's page from `check --html`: the same sections and grid, no server.
    let html = dir.path().join("part.html");
    let out = meshvol(&["check", p(&part), "--html", p(&html)]);
    assert_eq!(out.status.code(), Some(0));
    browser.open(&format!("file://{}", p(&html)));
    let shown = card(&browser, p(&part));
    assert_agrees(&shown, &part, false);
    assert_slices_agree(&browser, &part, &shots, "part-html-slices");
    eprintln!("screenshots in {}", shots.display());
}
