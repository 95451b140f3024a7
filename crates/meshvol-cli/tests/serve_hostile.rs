//! `meshvol serve` against hostile clients: slow headers and bodies, idle connections,
//! foreign hosts and pages, uploads that cost far more than their size, too many
//! requests at once, a check past its time, settings that are wrong, and a stop signal. Each hostile request must get a JSON error (or be
//! closed) and free what it took; a normal upload must still be answered with the
//! right numbers (a box's volume, known in closed form).
//!
//! No assertion is on a duration: the timeouts are configured short (1 s) or long
//! (60 s) so that the outcome asserted cannot depend on how loaded the machine is.

mod common;

use common::server::{agent, peak_memory_kib, Server};
use common::{box_obj, meshvol, three_mf};
use serde_json::Value;
use std::io::{ErrorKind, Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};

fn json(body: &str) -> Value {
    serde_json::from_str(body).unwrap_or_else(|e| panic!("not JSON ({e}): {body}"))
}

/// The address of `server`, `127.0.0.1:PORT`.
fn address(server: &Server) -> &str {
    server.url.trim_start_matches("http://")
}

/// Sends `head` (without its blank line), then `body`, on a new connection, asking for
/// it to be closed after the answer: the status and the answer's body.
fn raw(server: &Server, head: &str, body: &[u8]) -> (u16, String) {
    let mut stream = TcpStream::connect(address(server)).unwrap();
    stream.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    let length = body.len();
    write!(stream, "{head}\r\nContent-Length: {length}\r\nConnection: close\r\n\r\n").unwrap();
    stream.write_all(body).unwrap();
    let mut answer = String::new();
    stream.read_to_string(&mut answer).unwrap();
    let status = answer.get(9..12).and_then(|s| s.parse().ok()).unwrap_or(0);
    let body = answer.split_once("\r\n\r\n").map_or("", |(_, b)| b).to_string();
    (status, body)
}

/// A box 2 × 3 × 4 (volume 24) as OBJ.
fn part() -> String {
    box_obj([0.0; 3], [2.0, 3.0, 4.0], 1, true, false)
}

/// Uploads the part the ordinary way: it must be measured right.
fn normal_upload(server: &Server) {
    let (status, body) = server.post("/api/check?name=part.obj", part().as_bytes());
    assert_eq!(status, 200, "{body}");
    assert_eq!(json(&body)["solid_volume"], 24.0, "{body}");
}

/// A connection that sent half a request header.
fn half_header(server: &Server) -> TcpStream {
    let mut stream = TcpStream::connect(address(server)).unwrap();
    write!(stream, "POST /api/check?name=a.obj HTTP/1.1\r\nHost: {}\r\nX-Slow: ", address(server))
        .unwrap();
    stream
}

/// A connection that sent a whole header announcing 100,000 bytes, and one byte.
fn slow_body(server: &Server) -> TcpStream {
    let mut stream = TcpStream::connect(address(server)).unwrap();
    let head = format!(
        "POST /api/check?name=a.obj HTTP/1.1\r\nHost: {}\r\nContent-Length: 100000\r\n\r\n#",
        address(server)
    );
    stream.write_all(head.as_bytes()).unwrap();
    stream
}

/// What the server sent on `stream` until it closed it (a reset counts as closed);
/// panics if it is still open after 60 s.
fn until_closed(mut stream: TcpStream) -> String {
    stream.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    let mut got = Vec::new();
    match stream.read_to_end(&mut got) {
        Ok(_) => {}
        Err(e) if e.kind() == ErrorKind::ConnectionReset => {}
        Err(e) => panic!("the server kept the connection open: {e}"),
    }
    String::from_utf8_lossy(&got).into_owned()
}

/// With one check at a time, 200 half headers and 8 bodies sent a byte at a time hold
/// no check: an upload is answered while they are all still open (their timeout is
/// 60 s, and none has been answered).
#[test]
fn slow_clients_do_not_hold_a_check() {
    let server = Server::start(&["--max-concurrent", "1", "--client-timeout", "60"]);
    let halves: Vec<TcpStream> = (0..200).map(|_| half_header(&server)).collect();
    let slow: Vec<TcpStream> = (0..8).map(|_| slow_body(&server)).collect();
    let start = Instant::now();
    normal_upload(&server);
    eprintln!("answered in {:.2} s beside 208 slow clients", start.elapsed().as_secs_f64());
    for stream in &slow {
        stream.set_nonblocking(true).unwrap();
        let mut byte = [0u8; 1];
        let peeked = stream.peek(&mut byte);
        assert!(
            matches!(&peeked, Err(e) if e.kind() == ErrorKind::WouldBlock),
            "a slow body was answered or closed before the upload: {peeked:?}"
        );
    }
    drop((halves, slow));
}

/// With a client timeout of 1 s: half headers, bodies a byte at a time, connections
/// that send nothing and kept-alive connections left idle are all closed, a slow body
/// with a 408 naming the rate; meanwhile uploads are answered.
#[test]
fn slow_and_idle_clients_are_closed() {
    let server = Server::start(&["--client-timeout", "1"]);
    let halves: Vec<TcpStream> = (0..200).map(|_| half_header(&server)).collect();
    let slow: Vec<TcpStream> = (0..8).map(|_| slow_body(&server)).collect();
    let silent: Vec<TcpStream> =
        (0..300).map(|_| TcpStream::connect(address(&server)).unwrap()).collect();
    let idle: Vec<TcpStream> = (0..10)
        .map(|_| {
            let mut stream = TcpStream::connect(address(&server)).unwrap();
            write!(stream, "GET /api/limits HTTP/1.1\r\nHost: {}\r\n\r\n", address(&server))
                .unwrap();
            stream
        })
        .collect();
    normal_upload(&server);
    for stream in halves.into_iter().chain(silent) {
        until_closed(stream);
    }
    for stream in slow {
        let answer = until_closed(stream);
        assert!(answer.starts_with("HTTP/1.1 408"), "{answer}");
        let body = answer.split_once("\r\n\r\n").unwrap().1;
        assert!(json(body)["error"].as_str().unwrap().contains("--min-rate"), "{body}");
    }
    for stream in idle {
        // The first request is answered; then the connection is closed, idle.
        let answer = until_closed(stream);
        assert!(answer.starts_with("HTTP/1.1 200"), "{answer}");
    }
    normal_upload(&server);
}

#[test]
fn foreign_hosts_and_pages_are_refused() {
    let server = Server::start(&["--allow-host", "parts.shop"]);
    let obj = part();
    let post = |host: &str, origin: Option<&str>| {
        let origin = origin.map_or(String::new(), |o| format!("\r\nOrigin: {o}"));
        let head = format!("POST /api/check?name=part.obj HTTP/1.1\r\nHost: {host}{origin}");
        raw(&server, &head, obj.as_bytes())
    };
    let here = address(&server).to_string();
    // DNS rebinding: another name for this machine.
    let (status, body) = post("evil.example", None);
    assert_eq!(status, 421, "{body}");
    assert!(json(&body)["error"].as_str().unwrap().contains("--allow-host"), "{body}");
    let (status, body) =
        post(&format!("evil.example:{}", server.url.rsplit(':').next().unwrap()), None);
    assert_eq!(status, 421, "{body}");
    // A form or script on another site's page.
    for origin in ["http://evil.example", "null", "http://127.0.0.1:1"] {
        let (status, body) = post(&here, Some(origin));
        assert_eq!(status, 403, "{origin}: {body}");
        assert!(json(&body)["error"].is_string(), "{body}");
    }
    // The page itself, and a name allowed.
    let (status, body) = post(&here, Some(&format!("http://{here}")));
    assert_eq!((status, json(&body)["solid_volume"].as_f64()), (200, Some(24.0)), "{body}");
    let (status, body) = post("parts.shop:8765", Some("https://parts.shop"));
    assert_eq!((status, json(&body)["solid_volume"].as_f64()), (200, Some(24.0)), "{body}");
    let (status, body) = post("localhost", None);
    assert_eq!(status, 200, "{body}");
    // The page says where it may load from and send to.
    let mut response = agent().get(format!("{}/", server.url)).call().unwrap();
    let policy = response.headers().get("content-security-policy").unwrap().to_str().unwrap();
    assert!(policy.contains("default-src 'none'") && policy.contains("frame-ancestors 'none'"));
    assert!(response.body_mut().read_to_string().unwrap().contains("<title>meshvol"));
}

/// A 3MF placing a tetrahedron 10^levels times (components ten to a level): a few KB.
fn nested_components(levels: usize) -> Vec<u8> {
    let mut model = String::from(
        r#"<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>
        <object id="1" type="model"><mesh><vertices>
        <vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="1"/>
        </vertices><triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/>
        <triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles></mesh></object>"#,
    );
    for level in 1..=levels {
        let step = 2.0 * 10f64.powi(level as i32 - 1);
        model += &format!(r#"<object id="{}" type="model"><components>"#, level + 1);
        for i in 0..10 {
            model += &format!(
                r#"<component objectid="{level}" transform="1 0 0 0 1 0 0 0 1 {} 0 0"/>"#,
                step * i as f64
            );
        }
        model += "</components></object>";
    }
    model += &format!(r#"</resources><build><item objectid="{}"/></build></model>"#, levels + 1);
    three_mf(&model)
}

/// `bytes` compressed with gzip.
fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut encoder = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    encoder.write_all(bytes).unwrap();
    encoder.finish().unwrap()
}

/// `bytes` as the one member `name` of a deflated zip.
fn zipped(name: &str, bytes: &[u8]) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .compression_level(Some(9));
    zip.start_file(name, options).unwrap();
    zip.write_all(bytes).unwrap();
    zip.finish().unwrap().into_inner()
}

/// Asserts a 413 naming `budget` (the flag), in its key and its message.
fn over(answer: (u16, String), budget: &str) {
    let (status, body) = answer;
    assert_eq!(status, 413, "{body}");
    let v = json(&body);
    assert_eq!(v["budget"], budget, "{body}");
    assert!(v["error"].as_str().unwrap().contains(budget), "{body}");
}

/// Uploads that cost far more than their bytes are refused before the work, naming the
/// budget; the same files within the budgets are measured right; and the server's
/// peak memory stays far below what the refused work would have taken.
#[test]
fn uploads_past_a_budget_are_413_naming_it() {
    let server = Server::start(&[
        "--max-placements",
        "2000",
        "--max-inflated",
        "1MiB",
        "--max-faces",
        "50000",
    ]);
    // 10⁶ tetrahedra in a few KB (1,111,111 placements, components counted); 10³ of
    // them are measured (1/6 each: 1,111 placements).
    let million = nested_components(6);
    assert!(million.len() < 8 * 1024, "{}", million.len());
    over(server.post("/api/check?name=nested.3mf", &million), "--max-placements");
    let (status, body) = server.post("/api/check?name=nested.3mf", &nested_components(3));
    assert_eq!(status, 200, "{body}");
    let volume = json(&body)["solid_volume"].as_f64().unwrap();
    assert!((volume - 1000.0 / 6.0).abs() < 1e-9, "{volume}");
    // A gzip bomb: 256 MiB of one byte in about 256 KB.
    let bomb = gzip(&vec![b'#'; 256 << 20]);
    assert!(bomb.len() < (1 << 19), "{}", bomb.len());
    over(server.post("/api/check?name=bomb.obj.gz", &bomb), "--max-inflated");
    let (status, body) = server.post("/api/check?name=part.obj.gz", &gzip(part().as_bytes()));
    assert_eq!((status, json(&body)["solid_volume"].as_f64()), (200, Some(24.0)), "{body}");
    // A zip bomb, the same 256 MiB as the one member of a zip; a small zip is measured.
    let bomb = zipped("bomb.obj", &vec![b'#'; 256 << 20]);
    assert!(bomb.len() < (1 << 19), "{}", bomb.len());
    over(server.post("/api/check?name=bomb.zip", &bomb), "--max-inflated");
    let (status, body) =
        server.post("/api/check?name=part.zip", &zipped("part.obj", part().as_bytes()));
    assert_eq!((status, json(&body)["solid_volume"].as_f64()), (200, Some(24.0)), "{body}");
    // 10,000 boxes in a row: 60,000 faces, past the budget of 50,000.
    let mut many = String::new();
    for i in 0..10_000 {
        let x = 2.0 * i as f64;
        many += &box_obj([x, 0.0, 0.0], [x + 1.0, 1.0, 1.0], 8 * i + 1, true, false);
    }
    over(server.post("/api/check?name=many.obj", many.as_bytes()), "--max-faces");
    // 10⁶ tetrahedra expanded and checked would take hundreds of MB, the bomb 256 MiB.
    if let Some(peak) = peak_memory_kib(server.pid()) {
        eprintln!("the server's peak memory: {} MiB", peak / 1024);
        assert!(peak < 128 * 1024, "peak {peak} KiB");
    }
}

/// An answer larger than `--max-answer` is 413 naming it; a smaller one is the answer.
#[test]
fn an_answer_past_its_budget_is_413_naming_it() {
    let server = Server::start(&["--max-answer", "16KiB"]);
    // The page's answer holds 64 sections and a grid of cells: far more than 16 KiB.
    over(server.post("/api/view?name=part.obj", part().as_bytes()), "--max-answer");
    let (status, body) = server.post("/api/check?name=part.obj", part().as_bytes());
    assert!(body.len() < 16 * 1024, "{}", body.len());
    assert_eq!((status, json(&body)["solid_volume"].as_f64()), (200, Some(24.0)), "{body}");
}

#[test]
fn every_error_is_json() {
    let server = Server::start(&[]);
    let (status, body) = server.get("/api/check");
    assert_eq!(status, 405, "{body}");
    assert!(json(&body)["error"].as_str().unwrap().contains("GET"), "{body}");
    let (status, body) = server.get("/no/such/page");
    assert_eq!(status, 404, "{body}");
    assert!(json(&body)["error"].is_string(), "{body}");
    let head = format!(
        "POST /api/check?name=part.obj HTTP/1.1\r\nHost: {}\r\nContent-Encoding: gzip",
        address(&server)
    );
    let (status, body) = raw(&server, &head, &gzip(part().as_bytes()));
    assert_eq!(status, 415, "{body}");
    assert!(json(&body)["error"].as_str().unwrap().contains("Content-Encoding"), "{body}");
    // A misspelt option is refused, naming it, not measured without.
    let (status, body) = server.post("/api/check?name=part.obj&unit=mm", part().as_bytes());
    assert_eq!(status, 400, "{body}");
    assert!(json(&body)["error"].as_str().unwrap().contains("`unit`"), "{body}");
    let boundary = "XyZ";
    let mut form = format!(
        "--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; filename=\"part.obj\"\r\n\r\n{}\r\n\
         --{boundary}\r\nContent-Disposition: form-data; name=\"unitz\"\r\n\r\nmm:cm\r\n--{boundary}--\r\n",
        part()
    );
    let kind = format!("multipart/form-data; boundary={boundary}");
    let (status, body) = server.post_typed("/api/check", form.as_bytes(), &kind);
    assert_eq!(status, 400, "{body}");
    assert!(json(&body)["error"].as_str().unwrap().contains("`unitz`"), "{body}");
    form = form.replace("unitz", "units");
    let (status, body) = server.post_typed("/api/check", form.as_bytes(), &kind);
    // 24 mm³ is 0.024 cm³.
    let volume = json(&body)["solid_volume"].as_f64();
    assert!(status == 200 && volume.is_some_and(|v| (v - 0.024).abs() < 1e-15), "{body}");
    let (status, body) = server.post("/api/check?name=part.obj", b"v 1 2\nf 1 2 3\n");
    assert_eq!(status, 422, "{body}");
    assert!(json(&body)["error"].is_string(), "{body}");
}

#[test]
fn bad_settings_refuse_to_start_naming_them() {
    let out = std::process::Command::new(common::bin())
        .args(["serve", "--port", "0"])
        .env("MESHVOL_MAX_STREAM_BYTES", "256MiB")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.contains("MESHVOL_MAX_STREAM_BYTES=256MiB"), "{stderr}");
    assert!(!stderr.contains("serving on"), "{stderr}");
    let out = meshvol(&["serve", "--port", "0", "--max-upload", "1MiB", "--max-buffered", "1KiB"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("--max-buffered"), "{stderr}");
    for (flag, value) in [("--min-rate", "0"), ("--client-timeout", "0"), ("--max-faces", "0")] {
        let out = meshvol(&["serve", "--port", "0", flag, value]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && stderr.contains(flag), "{flag}: {stderr}");
    }
}

/// SIGTERM and SIGINT stop the server: it exits 0 and its temporary folder is gone.
#[test]
fn a_stop_signal_removes_the_temporary_folder() {
    for signal in ["TERM", "INT"] {
        let temp = tempfile::tempdir().unwrap();
        let server = Server::start_in_env(&[], &[("TMPDIR", temp.path().to_str().unwrap())]);
        normal_upload(&server);
        let made: Vec<_> = std::fs::read_dir(temp.path()).unwrap().collect();
        assert_eq!(made.len(), 1, "the server's folder: {made:?}");
        let status = server.stop(signal);
        assert!(status.success(), "SIG{signal}: {status:?}");
        let left: Vec<_> = std::fs::read_dir(temp.path()).unwrap().collect();
        assert!(left.is_empty(), "SIG{signal} left {left:?}");
    }
}

/// Opens a request that announces a body and never sends it: it holds a place (the
/// body is read holding one) until its client timeout.
fn stalled(server: &Server) -> std::net::TcpStream {
    let address = address(server);
    let mut stream = std::net::TcpStream::connect(address).unwrap();
    write!(
        stream,
        "POST /api/check?name=slow.obj HTTP/1.1\r\nHost: {address}\r\nContent-Length: 100\r\n\r\n"
    )
    .unwrap();
    stream
}

#[test]
fn too_many_at_once_is_503_with_a_message() {
    // A time limit no check here comes near, however busy the machine.
    let server = Server::start(&["--max-concurrent", "1", "--queue", "0", "--timeout", "600"]);
    let cube = box_obj([0.0; 3], [1.0; 3], 1, true, false);
    // Until the stalled request holds the one place, a request may still get it; then
    // every one is turned away at once. On a busy machine a check may take the place
    // first, and the stalled request is itself turned away: then stall another.
    for attempt in 0.. {
        let slow = stalled(&server);
        let busy = (0..200).find_map(|_| {
            let (status, body) = server.post("/api/check?name=box.obj", cube.as_bytes());
            (status == 503).then_some(body)
        });
        if let Some(busy) = busy {
            assert!(json(&busy)["error"].as_str().unwrap().starts_with("busy: "), "{busy}");
            drop(slow);
            break;
        }
        assert!(attempt < 20, "no stalled request ever took the place");
    }
}

#[test]
fn a_request_past_the_time_limit_is_503_and_frees_its_place() {
    // A limit of 1 ms, which no check of 12,000 boxes (72,000 faces) keeps to.
    let server = Server::start(&["--max-concurrent", "1", "--queue", "0", "--timeout", "0.001"]);
    let many: String = (0..12_000)
        .map(|i| {
            let x = 2.0 * i as f64;
            box_obj([x, 0.0, 0.0], [x + 1.0, 1.0, 1.0], 8 * i + 1, true, false)
        })
        .collect();
    // Three in turn: each gets the one place once the check before it has stopped
    // (until then it is turned away as busy, the connection closed before all its
    // bytes are sent), and is answered 503 past its time.
    let url = format!("{}/api/check?name=many.obj", server.url);
    for _ in 0..3 {
        let late = (0..600).find_map(|_| {
            let sent = agent().post(&url).send(many.as_bytes());
            let body = sent.ok().and_then(|mut r| {
                assert_eq!(r.status(), 503);
                r.body_mut().read_to_string().ok()
            });
            let message = body.map(|b| json(&b)["error"].as_str().unwrap().to_string());
            match message {
                Some(late) if !late.starts_with("busy: ") => Some(late),
                _ => {
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    None
                }
            }
        });
        let late = late.expect("the place was never freed");
        assert!(late.contains("longer than the limit of 0.001 s (--timeout"), "{late}");
    }
}
