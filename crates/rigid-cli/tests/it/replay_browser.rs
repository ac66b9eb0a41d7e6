//! The `--html` replay in a real headless browser (Debian's `chromium`, driven through the
//! Chrome DevTools protocol over `--remote-debugging-pipe`), and the PNG plot:
//!
//! - the page loads with no console error, no exception and no network request (a strict
//!   Content-Security-Policy forbids them; every request the browser makes is recorded);
//! - screenshots at t = 0 and t = end show the robot: pixels of its colours where each link's
//!   origin is drawn (`replay.screen(i)`), and the two pictures differ;
//! - moving the slider moves the pose (the frame and the picture change);
//! - a body resting on the ground (`--ground`) has green force arrows, as long as its forces at
//!   the scale the page states, their vertical parts summing to its weight within 1 %;
//! - the PNG plot of the same run is not blank and has four panels.
//!
//! The PNG is checked in every run; the browser is a live check, run when `RIGID_CROSSCHECK=1`
//! (`scripts/setup.sh`, run by the README's test command, installs `chromium`; without it on the
//! PATH the test fails, saying so).

#![cfg(unix)]

use base64::Engine;
use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Write};
use std::os::unix::io::FromRawFd;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{channel, Receiver};
use std::time::{Duration, Instant};

const WIDTH: u32 = 800;
const HEIGHT: u32 = 600;
const BACKGROUND: [u8; 3] = [244, 245, 247];

fn chromium() -> Option<PathBuf> {
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .find_map(|name| {
            std::env::var_os("PATH").and_then(|paths| {
                std::env::split_paths(&paths)
                    .map(|d| d.join(name))
                    .find(|p| p.is_file())
            })
        })
}

/// A browser driven over `--remote-debugging-pipe`: commands on fd 3, replies on fd 4, each a
/// JSON message ended by a NUL byte.
struct Browser {
    child: Child,
    to: std::fs::File,
    from: Receiver<Value>,
    next_id: u64,
    session: Option<String>,
    events: Vec<Value>,
}

fn pipe() -> (i32, i32) {
    let mut fds = [0; 2];
    // SAFETY: `fds` is a valid array of two ints.
    assert_eq!(unsafe { libc::pipe2(fds.as_mut_ptr(), libc::O_CLOEXEC) }, 0);
    (fds[0], fds[1])
}

impl Browser {
    fn launch(exe: &Path, profile: &Path) -> Self {
        let (cmd_r, cmd_w) = pipe();
        let (resp_r, resp_w) = pipe();
        let mut command = Command::new(exe);
        command
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--enable-unsafe-swiftshader",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                "--disable-extensions",
                "--remote-debugging-pipe",
                &format!("--user-data-dir={}", profile.display()),
                &format!("--window-size={WIDTH},{HEIGHT}"),
                "about:blank",
            ])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null());
        // SAFETY: only async-signal-safe calls (fcntl, dup2) between fork and exec. The ends are
        // first copied above fd 10 (the copies are not close-on-exec), so that `dup2` onto 3
        // and 4 works even when a pipe end already is fd 3 or 4.
        unsafe {
            command.pre_exec(move || {
                let (a, b) = (
                    libc::fcntl(cmd_r, libc::F_DUPFD, 10),
                    libc::fcntl(resp_w, libc::F_DUPFD, 10),
                );
                if a < 0 || b < 0 || libc::dup2(a, 3) < 0 || libc::dup2(b, 4) < 0 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
        let child = command.spawn().expect("cannot start chromium");
        // SAFETY: the fds are ours, each wrapped once.
        let (to, from_file) = unsafe {
            libc::close(cmd_r);
            libc::close(resp_w);
            (
                std::fs::File::from_raw_fd(cmd_w),
                std::fs::File::from_raw_fd(resp_r),
            )
        };
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(from_file);
            loop {
                let mut buf = Vec::new();
                match r.read_until(0, &mut buf) {
                    Ok(0) | Err(_) => break,
                    Ok(_) => {
                        buf.pop();
                        if let Ok(v) = serde_json::from_slice::<Value>(&buf) {
                            if tx.send(v).is_err() {
                                break;
                            }
                        }
                    }
                }
            }
        });
        Self {
            child,
            to,
            from: rx,
            next_id: 1,
            session: None,
            events: Vec::new(),
        }
    }

    /// Send a command (to the page session once attached) and wait for its reply.
    fn call(&mut self, method: &str, params: Value) -> Value {
        let id = self.next_id;
        self.next_id += 1;
        let mut msg = json!({"id": id, "method": method, "params": params});
        if let Some(s) = &self.session {
            msg["sessionId"] = json!(s);
        }
        let mut bytes = serde_json::to_vec(&msg).unwrap();
        bytes.push(0);
        self.to.write_all(&bytes).unwrap();
        let deadline = Instant::now() + Duration::from_secs(60);
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let v = self
                .from
                .recv_timeout(left)
                .unwrap_or_else(|_| panic!("no reply to {method} within 60 s"));
            if v["id"] == json!(id) {
                assert!(v.get("error").is_none(), "{method}: {}", v["error"]);
                return v["result"].clone();
            }
            self.events.push(v);
        }
    }

    /// Attach to the page, enable the domains whose events the tests check, and load `html`
    /// paused at its first frame.
    fn open(&mut self, html: &Path) {
        let targets = self.call("Target.getTargets", json!({}));
        let page = targets["targetInfos"]
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["type"] == "page")
            .expect("a page target")["targetId"]
            .clone();
        let attached = self.call(
            "Target.attachToTarget",
            json!({"targetId": page, "flatten": true}),
        );
        self.session = Some(attached["sessionId"].as_str().unwrap().to_string());
        for domain in [
            "Runtime.enable",
            "Log.enable",
            "Network.enable",
            "Page.enable",
        ] {
            self.call(domain, json!({}));
        }
        self.call(
            "Emulation.setDeviceMetricsOverride",
            json!({"width": WIDTH, "height": HEIGHT, "deviceScaleFactor": 1, "mobile": false}),
        );
        let url = format!("file://{}?paused", html.display());
        self.call("Page.navigate", json!({"url": url}));
        self.wait_for(
            "document.readyState === 'complete' && !!window.replay && window.replay.ready",
        );
    }

    /// Asserts that nothing went wrong in the page (no exception, no console error) and that
    /// nothing but the page itself was fetched.
    fn assert_clean(&self, html: &Path) {
        let page_url = format!("file://{}", html.display());
        for e in &self.events {
            let m = e["method"].as_str().unwrap_or("");
            match m {
                "Runtime.exceptionThrown" => panic!("exception in the page: {}", e["params"]),
                "Runtime.consoleAPICalled" if e["params"]["type"] == "error" => {
                    panic!("console error: {}", e["params"])
                }
                "Log.entryAdded" if e["params"]["entry"]["level"] == "error" => {
                    panic!("console error: {}", e["params"]["entry"])
                }
                "Network.requestWillBeSent" => {
                    let u = e["params"]["request"]["url"].as_str().unwrap_or("");
                    assert!(
                        u.starts_with(&page_url),
                        "the page made a network request: {u}"
                    );
                }
                _ => {}
            }
        }
    }

    /// Evaluate a JavaScript expression in the page; its value.
    fn eval(&mut self, expr: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({"expression": expr, "returnByValue": true, "awaitPromise": true}),
        );
        assert!(
            r.get("exceptionDetails").is_none(),
            "{expr}: {}",
            r["exceptionDetails"]
        );
        r["result"]["value"].clone()
    }

    /// Wait until the expression is true.
    fn wait_for(&mut self, expr: &str) {
        let deadline = Instant::now() + Duration::from_secs(60);
        while self.eval(expr) != json!(true) {
            assert!(Instant::now() < deadline, "timed out waiting for {expr}");
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// A screenshot as RGB rows.
    fn screenshot(&mut self) -> Image {
        // two frames, so that the last draw is on screen
        self.eval(
            "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r(true))))",
        );
        let r = self.call("Page.captureScreenshot", json!({"format": "png"}));
        let png = base64::engine::general_purpose::STANDARD
            .decode(r["data"].as_str().unwrap())
            .unwrap();
        decode_png(&png)
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

struct Image {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Image {
    fn px(&self, x: usize, y: usize) -> [u8; 3] {
        let i = 3 * (y * self.width + x);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }
}

fn decode_png(bytes: &[u8]) -> Image {
    let mut dec = png::Decoder::new(std::io::Cursor::new(bytes));
    dec.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let rgb = buf[..info.buffer_size()]
        .chunks(channels)
        .flat_map(|p| match channels {
            1 | 2 => [p[0], p[0], p[0]],
            _ => [p[0], p[1], p[2]],
        })
        .collect();
    Image {
        width: info.width as usize,
        height: info.height as usize,
        rgb,
    }
}

/// A pixel of a robot's body: far from the background and not a light grey grid line.
fn is_robot(p: [u8; 3]) -> bool {
    let d = (0..3)
        .map(|k| (p[k] as i32 - BACKGROUND[k] as i32).abs())
        .max()
        .unwrap();
    let light_grey =
        p.iter().all(|&c| c > 185) && p.iter().max().unwrap() - p.iter().min().unwrap() < 20;
    d > 40 && !light_grey
}

/// The model: a two-link arm with a box, a cylinder, a sphere, a capsule and an STL mesh (a
/// tetrahedron), swinging under gravity.
fn write_robot(dir: &Path) -> PathBuf {
    std::fs::write(
        dir.join("tetra.stl"),
        "solid t\n\
         facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 0.1 0\nvertex 0.1 0 0\nendloop\nendfacet\n\
         facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0 0.1\nendloop\nendfacet\n\
         facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0.1\nvertex 0 0.1 0\nendloop\nendfacet\n\
         facet normal 1 1 1\nouter loop\nvertex 0.1 0 0\nvertex 0 0.1 0\nvertex 0 0 0.1\nendloop\nendfacet\n\
         endsolid t\n",
    )
    .unwrap();
    let urdf = r#"<robot name="arm">
  <material name="blue"><color rgba="0.2 0.4 0.8 1"/></material>
  <link name="base"><visual><geometry><box size="0.3 0.3 0.1"/></geometry><material name="blue"/></visual></link>
  <link name="upper">
    <inertial><origin xyz="0 0 -0.25"/><mass value="1"/><inertia ixx="0.02" iyy="0.02" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0 0 -0.25"/><geometry><cylinder radius="0.04" length="0.5"/></geometry><material name="orange"><color rgba="0.9 0.5 0.1 1"/></material></visual>
    <visual><geometry><sphere radius="0.06"/></geometry><material name="blue"/></visual>
  </link>
  <link name="lower">
    <inertial><origin xyz="0 0 -0.2"/><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0 0 -0.2"/><geometry><capsule radius="0.035" length="0.3"/></geometry><material name="green"><color rgba="0.2 0.7 0.3 1"/></material></visual>
    <visual><geometry><sphere radius="0.05"/></geometry><material name="blue"/></visual>
    <visual><origin xyz="0 0 -0.45"/><geometry><mesh filename="tetra.stl" scale="1 1 1"/></geometry><material name="red"><color rgba="0.8 0.1 0.1 1"/></material></visual>
  </link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><origin xyz="0 0 1"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="10"/></joint>
  <joint name="elbow" type="continuous"><parent link="upper"/><child link="lower"/><origin xyz="0 0 -0.5"/><axis xyz="0 1 0"/></joint>
</robot>"#;
    let path = dir.join("arm.urdf");
    std::fs::write(&path, urdf).unwrap();
    path
}

/// `rigid simulate` of the arm for 1.5 s with `--html` and `--plot` into a fresh folder named
/// `tag`: `(folder, page, plot)`, after checking that it succeeds without a warning.
fn simulate_arm(tag: &str) -> (PathBuf, PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("rigid_replay_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let urdf = write_robot(&dir);
    let (html, plot) = (dir.join("arm.html"), dir.join("arm.png"));
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .arg("simulate")
        .arg(&urdf)
        .args(["--q0", "1.2,0.3", "--duration", "1.5", "--html"])
        .arg(&html)
        .arg("--plot")
        .arg(&plot)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        !String::from_utf8_lossy(&out.stderr).contains("warning"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (dir, html, plot)
}

#[test]
fn png_plot_is_not_blank_and_has_four_panels() {
    let (dir, _, plot) = simulate_arm("png");
    // the PNG plot: not blank, four panels of 280 px, each with curves and axes
    let img = decode_png(&std::fs::read(&plot).unwrap());
    assert_eq!((img.width, img.height), (1000, 4 * 280));
    for band in 0..4 {
        let ink = (band * 280..(band + 1) * 280)
            .flat_map(|y| (0..img.width).map(move |x| (x, y)))
            .filter(|&(x, y)| img.px(x, y).iter().any(|&c| c < 200))
            .count();
        assert!(ink > 2000, "panel {band}: {ink} drawn pixels");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn replay_page_shows_the_moving_robot_in_a_browser_without_errors_or_requests() {
    if !crate::common::live("the HTML replay in chromium") {
        return;
    }
    let exe = chromium().expect(
        "no chromium on PATH: RIGID_CROSSCHECK=1 tests the replay page in a browser: \
         `apt-get install chromium` (bash scripts/test.sh does)",
    );
    let (dir, html, _) = simulate_arm("page");

    let mut b = Browser::launch(&exe, &dir.join("profile"));
    b.open(&html);
    let nframes = b.eval("replay.nframes").as_u64().unwrap();
    let nodes = b.eval("replay.nodes").as_u64().unwrap();
    assert_eq!(nodes, 3, "base, upper and lower links");
    assert!(nframes >= 90, "1.5 s at 60 fps: {nframes} frames");

    // robot pixels at every link origin, t = 0 and t = end
    let mut shots = Vec::new();
    for (label, set) in [("t = 0", "replay.setFrame(0)"), ("t = end", "")] {
        if set.is_empty() {
            // the slider, as a user moves it
            b.eval(
                "(() => { const s = document.getElementById('slider'); s.value = s.max; \
                 s.dispatchEvent(new Event('input')); return true; })()",
            );
            assert_eq!(
                b.eval("replay.frame()").as_u64().unwrap(),
                nframes - 1,
                "the slider sets the frame"
            );
        } else {
            b.eval(set);
        }
        let img = b.screenshot();
        assert_eq!((img.width, img.height), (WIDTH as usize, HEIGHT as usize));
        for i in 0..nodes {
            let xy = b.eval(&format!("replay.screen({i})"));
            let (x, y) = (xy[0].as_f64().unwrap(), xy[1].as_f64().unwrap());
            let hit = (-3i32..=3).any(|dy| {
                (-3i32..=3).any(|dx| {
                    let (px, py) = (x as i32 + dx, y as i32 + dy);
                    px >= 0
                        && py >= 0
                        && (px as usize) < img.width
                        && (py as usize) < img.height
                        && is_robot(img.px(px as usize, py as usize))
                })
            });
            assert!(
                hit,
                "{label}: no robot pixel at link {i}'s origin ({x:.0}, {y:.0})"
            );
        }
        let robot = img
            .rgb
            .chunks(3)
            .filter(|p| is_robot([p[0], p[1], p[2]]))
            .count();
        eprintln!("{label}: {robot} robot pixels");
        assert!(robot > 1500, "{label}: {robot} robot pixels");
        shots.push(img);
    }
    let moved = shots[0]
        .rgb
        .chunks(3)
        .zip(shots[1].rgb.chunks(3))
        .filter(|(a, b)| (0..3).any(|k| (a[k] as i32 - b[k] as i32).abs() > 30))
        .count();
    eprintln!(
        "t = 0 and t = end differ in {moved} pixels; {} events",
        b.events.len()
    );
    assert!(
        moved > 1000,
        "t = 0 and t = end differ in {moved} pixels only"
    );

    b.assert_clean(&html);
    drop(b);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The number of pixels of the force arrows' green (far greener than red and blue).
fn green_pixels(img: &Image) -> usize {
    img.rgb
        .chunks(3)
        .filter(|p| p[1] as i32 > p[0] as i32 + 60 && p[1] as i32 > p[2] as i32 + 40)
        .count()
}

#[test]
fn replay_page_draws_the_contact_forces_as_arrows_at_the_stated_scale() {
    if !crate::common::live("the contact force arrows in chromium") {
        return;
    }
    let exe = chromium().expect("no chromium on PATH (RIGID_CROSSCHECK=1 needs it)");
    let dir = std::env::temp_dir().join(format!("rigid_replay_arrows_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let html = dir.join("compound.html");
    let spec = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/compound.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .arg("simulate")
        .arg(&spec)
        .args(["--ground", "--duration", "1", "--html"])
        .arg(&html)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut b = Browser::launch(&exe, &dir.join("profile"));
    b.open(&html);
    // frame 0 comes before the first step: no force, no arrow
    assert_eq!(b.eval("replay.arrows().length"), json!(0));
    let before = green_pixels(&b.screenshot());
    b.eval("replay.setFrame(replay.nframes - 1)");
    let after = green_pixels(&b.screenshot());
    eprintln!("green pixels: {before} at t = 0, {after} at the end");
    assert!(after > before + 200, "{before} -> {after} green pixels");
    // the scale the page states, in mm per N
    let info = b.eval("document.getElementById('info').textContent");
    let info = info.as_str().unwrap();
    let mm_per_n: f64 = info
        .split(" mm per N")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no scale on the page: {info}"));
    // at rest, the drawn arrows: each as long as its force at that scale, their vertical parts
    // together as long as the 3 kg compound's weight
    let arrows = b.eval("replay.arrows()");
    let arrows = arrows.as_array().unwrap();
    assert!(!arrows.is_empty());
    let mut up = 0.0;
    for a in arrows {
        let (length, force) = (a["length"].as_f64().unwrap(), a["force"].as_f64().unwrap());
        assert!(
            (length - 1e-3 * mm_per_n * force).abs() < 1e-4 * length,
            "{a}"
        );
        up += length * a["dir"][2].as_f64().unwrap();
    }
    let weight = 1e-3 * mm_per_n * 3.0 * 9.81;
    assert!(
        (up - weight).abs() < 0.01 * weight,
        "{up} m of arrows up, weight {weight} m"
    );
    b.assert_clean(&html);
    drop(b);
    let _ = std::fs::remove_dir_all(&dir);
}
