// Runs the X_ITE browser in headless Chromium on scenes and records each one's trace
// (docs/implementers.md's format) through X_ITE's scripting API, under a virtual clock
// (page.html) so that frame k falls at k / frameRate and runs are bit-identical.
//
//   node record.mjs JOB.json
//
// JOB: {"chromium": PATH, "runs": [{"scene", "out", "frameRate", "duration", "loadFrames",
//        "collections": [NAME...], "bodies": [NAME...], "joints": {NAME: [FIELD...]},
//        "sensors": [NAME...]}]}
// Prints one JSON line per run, as it ends: {"run", "ok", "frames", "blewUp", "wallSeconds",
// "messages"} (blewUp: the first output that was not finite, where the trace stops; or null)
// or {"run", "ok": false, "error", "messages"}. Nothing is fetched from the
// network: the page, X_ITE and the scene's folder are served from disk by request routing,
// and every other request is refused.
import { readFileSync, writeFileSync } from "node:fs";
import { dirname, extname, join, normalize, sep } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const HERE = dirname(fileURLToPath(import.meta.url));
const ORIGIN = "http://x3drbp.test";
const X_ITE = join(HERE, "node_modules", "x_ite", "dist");
const FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
  "--disable-background-networking", "--disable-component-update", "--disable-sync",
  "--use-angle=swiftshader", "--enable-unsafe-swiftshader"];
const TYPES = {".html": "text/html", ".js": "text/javascript", ".mjs": "text/javascript",
  ".wasm": "application/wasm", ".css": "text/css", ".json": "application/json",
  ".x3d": "model/x3d+xml", ".x3dv": "model/x3d+vrml", ".x3dj": "model/x3d+json"};

function serve(root, rest) {
  const file = normalize(join(root, decodeURIComponent(rest)));
  if (file !== root && !file.startsWith(root + sep)) return null;
  try {
    return { body: readFileSync(file), contentType: TYPES[extname(file)] ?? "application/octet-stream" };
  } catch {
    return null;
  }
}

// In the page: load the scene with the clock stopped, then step it frame by frame.
async function record(run) {
  const fmt = v => {
    if (v === null || v === undefined) return "NULL";
    if (typeof v === "boolean") return v ? "true" : "false";
    if (typeof v === "number") return String(v);
    if (typeof v.getNodeName === "function") return v.getNodeName() || "NULL";
    if ("angle" in v) {  // the trace wants a unit axis: X_ITE hands back the axis as given, or
      // for a tiny angle, a float32 one off by up to 10%
      const n = Math.hypot(v.x, v.y, v.z);
      return n > 0 ? `${v.x / n} ${v.y / n} ${v.z / n} ${v.angle}` : `0 0 1 ${v.angle}`;
    }
    if ("z" in v) return `${v.x} ${v.y} ${v.z}`;
    if ("y" in v) return `${v.x} ${v.y}`;
    return String(v);
  };
  const quote = s => /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
  const canvas = document.querySelector("x3d-canvas");
  const browser = canvas.browser;
  const periodMs = 1000 / run.frameRate;
  // X_ITE's own MaximumFrameRate (80) stays: a frame comes at most every 1/80 s, as in any
  // X_ITE, and the harness asks for no faster rate (harness.reachable_rate)
  // Loading waits for frames of the empty world it replaces, so the clock runs at the
  // frame period while it loads; the scene is installed between two frames, and the state
  // read then is time 0: no physics step has been taken yet.
  const empty = browser.currentScene;
  let failed = null;
  browser.loadURL(new X3D.MFString(run.url)).catch(error => { failed = error; });
  let k0 = 0;
  while (browser.currentScene === empty && failed === null) {
    if (++k0 > run.loadFrames) throw new Error(`the scene did not load in ${run.loadFrames} frames`);
    window.x3drbpClock.frame(k0, periodMs);
    await new Promise(resolve => setTimeout(resolve, 1));
  }
  if (failed !== null) throw failed;
  // How many frames loading took varies from run to run, and with it the clock's value, and
  // so the last bits of every frame interval X_ITE computes (t_k - t_(k-1) in seconds). So
  // the collections are held disabled for one frame at a fixed time after any load can end,
  // and the run's frames count from there: frame k at EPOCH + (loadFrames + 1 + k) periods.
  const collections = run.collections.map(name => browser.currentScene.getNamedNode(name));
  collections.forEach(c => { c.enabled = false; });
  k0 = run.loadFrames + 1;
  window.x3drbpClock.frame(k0, periodMs);
  collections.forEach(c => { c.enabled = true; });
  const scene = browser.currentScene;
  const get = name => scene.getNamedNode(name);
  const bodies = run.bodies.map(get);
  const joints = Object.entries(run.joints).map(([name, fields]) => [name, get(name), fields]);
  const sensors = run.sensors.map(name => [name, get(name)]);
  const rows = ["time,node,field,value"];
  let blewUp = null;  // the first output that is not a finite number, where the run stops
  const add = (t, node, field, value) => {
    const text = fmt(value);
    if (blewUp === null && /NaN|Infinity/.test(text)) blewUp = `${node}.${field} is ${text} at ${t} s`;
    rows.push(`${t},${quote(node)},${quote(field)},${quote(text)}`);
  };
  const BODY = ["position", "orientation", "linearVelocity", "angularVelocity"];
  const CONTACT = ["position", "contactNormal", "depth", "body1", "body2", "geometry1", "geometry2"];
  const read = t => {
    bodies.forEach((b, i) => BODY.forEach(f => add(t, run.bodies[i], f, b[f])));
    for (const [name, j, fields] of joints) fields.forEach(f => add(t, name, f, j[f]));
    for (const [name, s] of sensors) {
      add(t, name, "isActive", s.isActive);
      const contacts = s.contacts;
      for (let i = 0; i < contacts.length; ++i)
        CONTACT.forEach(f => add(t, name, `contacts[${i}].${f}`, contacts[i][f]));
      const hits = s.intersections;
      for (let i = 0; i < hits.length; ++i) add(t, name, `intersections[${i}]`, hits[i]);
    }
  };
  const frames = Math.round(run.duration * run.frameRate);
  // a frame's rows go into the trace only when all are finite: the trace stays readable
  let kept = rows.length;
  read(0);
  let k = 0;
  while (blewUp === null && k < frames) {
    kept = rows.length;
    window.x3drbpClock.frame(k0 + ++k, periodMs);
    read(k / run.frameRate);
  }
  if (blewUp !== null) rows.length = kept;
  return { frames: blewUp === null ? k : Math.max(k - 1, 0), blewUp, text: rows.join("\n") + "\n" };
}

async function main() {
  const job = JSON.parse(readFileSync(process.argv[2], "utf8"));
  const chrome = await chromium.launch({ executablePath: job.chromium, args: FLAGS, headless: true });
  try {
    for (const [index, run] of job.runs.entries()) {
      const started = performance.now();
      const context = await chrome.newContext();
      const page = await context.newPage();
      const messages = [];
      page.on("console", m => { if (m.type() === "error" || m.type() === "warning") messages.push(m.text()); });
      page.on("pageerror", e => messages.push(String(e)));
      const sceneDir = dirname(run.scene);
      const sceneName = run.scene.slice(sceneDir.length + 1);
      await page.route("**/*", route => {
        const url = new URL(route.request().url());
        let found = null;
        if (url.origin === ORIGIN) {
          if (url.pathname === "/page.html") found = serve(HERE, "page.html");
          else if (url.pathname.startsWith("/x_ite/")) found = serve(X_ITE, url.pathname.slice(7));
          else if (url.pathname.startsWith("/scene/")) found = serve(sceneDir, url.pathname.slice(7));
        }
        return found ? route.fulfill({ status: 200, ...found }) : route.abort();
      });
      try {
        await page.goto(`${ORIGIN}/page.html`);
        await page.waitForFunction(() => document.querySelector("x3d-canvas")?.browser, null, { polling: 50 });
        const url = `${ORIGIN}/scene/${encodeURIComponent(sceneName)}`;
        const result = await page.evaluate(record, { ...run, url });
        writeFileSync(run.out, result.text);
        console.log(JSON.stringify({ run: index, ok: true, frames: result.frames, blewUp: result.blewUp,
          wallSeconds: (performance.now() - started) / 1000, messages }));
      } catch (error) {
        console.log(JSON.stringify({ run: index, ok: false, error: String(error).split("\n")[0], messages }));
      } finally {
        await context.close();
      }
    }
  } finally {
    await chrome.close();
  }
}

await main();
