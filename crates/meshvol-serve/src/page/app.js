// meshvol's page: sends each dropped file to POST /api/view, shows the reports
// (`check`'s and `volume`'s JSON, the same the command prints) and draws the checked
// solid with its problems. In a page written by `meshvol check --html`,
// window.MESHVOL_PAGE holds one file's content and nothing is sent anywhere.
"use strict";

const $ = (id) => document.getElementById(id);
const results = [];
let selected = -1;

// ---- numbers ----------------------------------------------------------------------
function fmt(x, digits = 8) {
  if (x === null || x === undefined) return "–";
  if (typeof x !== "number") return String(x);
  if (x === 0) return "0";
  const s = Math.abs(x) >= 1e-4 && Math.abs(x) < 1e12 ? x.toPrecision(digits) : x.toExponential(digits - 1);
  return s.includes("e") || !s.includes(".") ? s : s.replace(/0+$/, "").replace(/\.$/, "");
}
function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "class") e.className = v; else if (k.startsWith("data-")) e.setAttribute(k, v); else e[k] = v;
  }
  for (const c of children) if (c !== null && c !== undefined) e.append(c);
  return e;
}

// ---- the request --------------------------------------------------------------------
function unitsParam(fileUnit) {
  const file = fileUnit || $("units-file").value, report = $("units-report").value;
  if (!file && !report) return "";
  return file + (report ? ":" + report : "");
}
function densityParam() {
  return $("density").value.trim();
}
// A material turns volumes into masses, which needs the file's length unit: a file that
// does not declare one (STL, OBJ, PLY, OFF) is asked about, on its card, and measured
// again in the unit chosen, instead of failing with the command's advice.
const FILE_UNITS = [["mm", "mm"], ["cm", "cm"], ["m", "m"], ["in", "in"], ["ft", "ft"], ["um", "µm"]];
function needsUnit(body) {
  return densityParam() && !$("units-file").value && /length unit is not known/.test(body.error || "");
}
function askUnit(card, file) {
  card.replaceChildren(el("h2", {}, file.name));
  card.setAttribute("data-state", "asking");
  const buttons = FILE_UNITS.map(([value, label]) => {
    const b = el("button", { type: "button", "data-unit": value }, label);
    b.addEventListener("click", () => { card.remove(); send(file, value); });
    return b;
  });
  card.append(el("p", { class: "ask" }, "This file does not say its length unit, and a mass needs one. Its numbers are in:"), el("p", { class: "units" }, ...buttons));
}
async function send(file, fileUnit) {
  const q = new URLSearchParams({ name: file.name });
  if (unitsParam(fileUnit)) q.set("units", unitsParam(fileUnit));
  if (densityParam()) q.set("density", densityParam());
  const card = addCard({ name: file.name, pending: true });
  try {
    const response = await fetch("/api/view?" + q, { method: "POST", body: file });
    const body = await response.json().catch(() => ({ error: "HTTP " + response.status + " (no JSON)" }));
    if (!response.ok && !fileUnit && needsUnit(body)) return askUnit(card, file);
    if (!response.ok) return fillCard(card, { name: file.name, error: body.error || "HTTP " + response.status });
    fillCard(card, { name: file.name, page: body });
  } catch (e) {
    fillCard(card, { name: file.name, error: "cannot reach the server: " + e });
  }
}
async function sendAll(files) {
  const limit = window.MESHVOL_LIMITS ? window.MESHVOL_LIMITS.max_upload : Infinity;
  for (const f of files) {
    if (f.size > limit) {
      fillCard(addCard({ name: f.name }), { name: f.name, error: `${f.name}: ${f.size} bytes, more than the server takes (${limit} bytes)` });
      continue;
    }
    await send(f);
  }
}

// ---- the report cards ---------------------------------------------------------------
function addCard(r) {
  const card = el("article", { class: "card", "data-file": r.name }, el("h2", {}, r.name), el("p", { class: "status" }, "measuring…"));
  $("results").prepend(card);
  return card;
}
function fillCard(card, r) {
  card.replaceChildren(el("h2", {}, r.name));
  card.setAttribute("data-state", r.error ? "failed" : "done");
  if (r.error) {
    card.classList.add("failed");
    card.append(el("p", { class: "error" }, r.error));
    return;
  }
  const index = results.push(r.page) - 1;
  const c = r.page.check, v = r.page.volume;
  card.classList.add(c.bounds_a_volume ? "ok" : "bad");
  card.append(el("p", { class: "verdict" }, c.verdict));
  const u = c.units;
  const vu = u ? " " + u.volume : "", au = u ? " " + u.area : "", lu = u ? " " + u.length : "";
  const rows = [];
  const vol = v ? v.volume : c.solid_volume;
  const volCell = el("td", { class: "volume", "data-value": String(vol) }, fmt(vol) + vu);
  rows.push(["volume", volCell]);
  if (v && v.volume_error_bound > 0) rows.push(["rounding bound", "± " + fmt(v.volume_error_bound, 3) + vu]);
  if (c.volume_uncertainty > 0) rows.push(["capped holes", "± " + fmt(c.volume_uncertainty, 3) + vu + " (the caps' possible error)"]);
  if (v) rows.push(["area", el("td", { class: "area", "data-value": String(v.area) }, fmt(v.area) + au)]);
  if (v && c.mass !== undefined) rows.push(["mass", el("td", { class: "mass", "data-value": String(v.mass) }, fmt(v.mass) + (v.mass_unit ? " " + v.mass_unit : ""))]);
  if (v && v.bounds) {
    const size = v.bounds.max.map((m, i) => m - v.bounds.min[i]);
    rows.push(["size", size.map((s) => fmt(s, 6)).join(" × ") + lu]);
    rows.push(["bounds", "[" + v.bounds.min.map((x) => fmt(x, 6)).join(", ") + "] – [" + v.bounds.max.map((x) => fmt(x, 6)).join(", ") + "]"]);
  }
  if (v && v.centroid) rows.push(["centroid", v.centroid.map((x) => fmt(x, 6)).join(", ")]);
  rows.push(["shells", `${c.shells} (${c.cavities === 1 ? "1 cavity" : c.cavities + " cavities"})`]);
  const plural = (n, one, many) => `${n} ${n === 1 ? one : many}`;
  rows.push(["closed", c.closed ? "yes" : `no: ${plural(c.boundary_edges, "boundary edge", "boundary edges")} in ${plural(c.boundary_loops, "hole", "holes")}`]);
  rows.push(["manifold", c.non_manifold_edges ? `no: ${c.non_manifold_edges} non-manifold edges` : "yes"]);
  rows.push(["orientation", (c.orientation || "none") + (c.consistently_oriented ? "" : " (inconsistent)")]);
  rows.push(["self-intersections", c.self_intersections === null ? "not checked" : String(c.self_intersections)]);
  if (c.overlapping_shells.length) rows.push(["overlapping shells", c.overlapping_shells.map((p) => p.join(" & ")).join(", ")]);
  rows.push(["format", c.format || "–"]);
  rows.push(["units", u ? `file in ${u.file}${u.file_declared ? " (declared)" : ""}, reported in ${u.length}` : "unknown (choose the file's units)"]);
  const table = el("table", { class: "facts" });
  for (const [k, val] of rows) table.append(el("tr", {}, el("th", {}, k), val instanceof HTMLElement ? val : el("td", {}, val)));
  card.append(table);
  const warnings = (v ? v.warnings : c.warnings) || [];
  if (warnings.length) card.append(el("ul", { class: "warnings" }, ...warnings.map((w) => el("li", {}, w))));
  card.append(problemList(r.page, index));
  const json = el("pre", {}, JSON.stringify(c, null, 1));
  card.append(el("details", {}, el("summary", {}, "check --json"), json));
  card.addEventListener("click", () => select(index, card));
  select(index, card);
}

// The problems, each a click away from its place in the view: of each kind the first
// few and a count, the rest one click away ("show all"), so that a file with a thousand
// overlapping pairs gives a short list. The marks are characters every font has.
const FIRST_FEW = 5;
function problemList(page, index) {
  const list = el("ul", { class: "problems" });
  const view = page.view;
  const item = (text, kind, target) => {
    const li = el("li", { "data-kind": kind }, text);
    li.addEventListener("click", (e) => { e.stopPropagation(); selectIndex(index); viewer.frame(target); });
    return li;
  };
  const kind = (items, name) => {
    list.append(...items.slice(0, FIRST_FEW));
    if (items.length <= FIRST_FEW) return;
    const more = el("li", { class: "more", "data-more": name }, `… ${items.length - FIRST_FEW} more ${name} (${items.length} in all): show all`);
    more.addEventListener("click", (e) => { e.stopPropagation(); more.replaceWith(...items.slice(FIRST_FEW)); });
    list.append(more);
  };
  kind(loops(view).map((l, i) => item(`○ hole ${i + 1}: ${l.length} rim edges`, "hole", { edges: l })), "holes");
  const nm = [];
  for (let i = 0; i + 1 < view.non_manifold_edges.length; i += 2) {
    nm.push(item(`× non-manifold edge ${i / 2 + 1}`, "non-manifold", { edges: [[view.non_manifold_edges[i], view.non_manifold_edges[i + 1]]] }));
  }
  kind(nm, "non-manifold edges");
  kind(view.crossings.map((x) => item(`× faces ${x.faces[0]} and ${x.faces[1]} cross`, "crossing", { coords: x.triangles[0].concat(x.triangles[1]) })), "crossings");
  kind(view.overlapping_shells.map((p) => item(`∩ shells ${p[0]} and ${p[1]} overlap`, "overlap", { shells: p })), "overlapping pairs");
  kind(view.cavities.map((c) => item(`◦ cavity: shell ${c}`, "cavity", { shells: [c], clip: true })), "cavities");
  if (view.omitted) list.append(el("li", {}, "no view: " + view.omitted));
  return list;
}

// Boundary edges chained into loops (connected components of the rim edges).
function loops(view) {
  const e = view.boundary_edges, parent = new Map();
  const find = (a) => { while (parent.get(a) !== a) { parent.set(a, parent.get(parent.get(a))); a = parent.get(a); } return a; };
  for (const v of e) if (!parent.has(v)) parent.set(v, v);
  for (let i = 0; i < e.length; i += 2) parent.set(find(e[i]), find(e[i + 1]));
  const groups = new Map();
  for (let i = 0; i < e.length; i += 2) {
    const r = find(e[i]);
    if (!groups.has(r)) groups.set(r, []);
    groups.get(r).push([e[i], e[i + 1]]);
  }
  return [...groups.values()];
}

function selectIndex(index) {
  const card = [...document.querySelectorAll(".card[data-state=done]")].reverse()[index];
  if (card) select(index, card);
}
function select(index, card) {
  if (selected === index) return;
  selected = index;
  document.querySelectorAll(".card").forEach((c) => c.classList.remove("selected"));
  card.classList.add("selected");
  profile.show(results[index].profile);
  slices.show(results[index].slices);
  viewer.show(results[index].view);
}

// ---- the profile: volume below each level and section area, the level under the slider
const profile = {
  show(p) {
    this.p = p;
    $("profile").hidden = !p;
    if (!p) return;
    const n = p.levels.length, total = p.volume_below[n - 1] || 1;
    const maxArea = Math.max(...p.section_area.map(Math.abs)) || 1;
    const x = (k) => (n > 1 ? (600 * k) / (n - 1) : 0);
    const line = (ys, color) => {
      const pts = ys.map((y, k) => `${x(k).toFixed(1)},${(115 - 110 * y).toFixed(1)}`).join(" ");
      return `<polyline fill="none" stroke="${color}" stroke-width="2" vector-effect="non-scaling-stroke" points="${pts}"/>`;
    };
    $("profile-chart").innerHTML =
      line(p.volume_below.map((v) => v / total), "#2e90fa") +
      line(p.section_area.map((a) => Math.abs(a) / maxArea), "#f79009") +
      `<line id="profile-level" x1="600" x2="600" y1="0" y2="120" stroke="#101828" stroke-dasharray="3 3" vector-effect="non-scaling-stroke"/>`;
    this.at(1);
  },
  // The level nearest the fraction `f` of the height: its section area and volume below.
  at(f) {
    const p = this.p, label = $("section-at");
    if (!p) { label.textContent = ""; return; }
    const n = p.levels.length, k = Math.max(0, Math.min(n - 1, Math.round(f * (n - 1))));
    const u = p.units, total = p.volume_below[n - 1];
    const share = total ? ` (${fmt((100 * p.volume_below[k]) / total, 3)} %)` : "";
    // The words of the section's own label (`slices.label`): one wording for the level.
    label.textContent = `section at ${p.axis} = ${fmt(p.levels[k], 6)}${u ? " " + u.length : ""}: area ${fmt(p.section_area[k], 6)}${u ? " " + u.area : ""}, volume below ${fmt(p.volume_below[k], 6)}${u ? " " + u.volume : ""}${share}`;
    label.setAttribute("data-level", String(k));
    const marker = document.getElementById("profile-level");
    if (marker) { const xk = n > 1 ? (600 * k) / (n - 1) : 0; marker.setAttribute("x1", xk); marker.setAttribute("x2", xk); }
  },
};

// ---- the section and the grid slice at the slider's level --------------------------------
// The server (or `check --html`) cut the solid at 64 levels, one in the middle of each
// layer of a grid over it: `section`'s report and outline at each, and the grid's cell
// fractions. The slider picks a level; nothing is computed here.
const slices = {
  show(s) {
    this.s = s;
    $("slices").hidden = !s;
    if (s) this.at(this.level($("clip").value / 1000));
  },
  // The level whose grid layer holds the fraction `f` of the height (the top one at 1).
  level(f) {
    const n = this.s.levels.length;
    return Math.max(0, Math.min(n - 1, Math.floor(f * n)));
  },
  at(k) {
    if (!this.s) return;
    this.label(k);
    this.draw(k);
  },
  label(k) {
    const s = this.s, r = s.sections[k], u = r.units, lu = u ? " " + u.length : "";
    const label = $("cut-at");
    label.textContent = `section at z = ${fmt(r.plane.origin[2], 6)}${lu} (level ${k + 1} of ${s.levels.length}): ` +
      `area ${fmt(r.area)}${u ? " " + u.area : ""}, perimeter ${fmt(r.perimeter)}${lu}`;
    label.setAttribute("data-level", String(k));
    label.setAttribute("data-z", String(s.levels[k]));
    const g = s.grid, [nx, ny, nz] = g.cells, layer = s.layers[k], h = g.cell_size[2];
    const bottom = g.bounds.min[2] + layer * h;
    $("slice-caption").textContent = `grid ${nx} × ${ny} × ${nz} (meshvol grid --cells ${nx},${ny},${nz}), ` +
      `cells ${g.cell_size.map((c) => fmt(c, 4)).join(" × ")}${lu}; layer k = ${layer}: z from ${fmt(bottom, 6)} to ${fmt(bottom + h, 6)}${lu}`;
  },
  // The layer's cells to scale, x to the right and y up, and the section's outline over them.
  draw(k) {
    const s = this.s, canvas = $("grid-slice"), g = canvas.getContext("2d");
    const [nx, ny, nz] = s.grid.cells, layer = s.layers[k], [dx, dy] = s.cell;
    const scale = Math.min((canvas.width - 8) / (nx * dx), (canvas.height - 8) / (ny * dy));
    const x0 = (canvas.width - nx * dx * scale) / 2, y0 = (canvas.height + ny * dy * scale) / 2;
    const px = (i) => Math.round(x0 + i * dx * scale), py = (j) => Math.round(y0 - j * dy * scale);
    g.fillStyle = "#f2f4f7";
    g.fillRect(0, 0, canvas.width, canvas.height);
    for (let i = 0; i < nx; i++) {
      for (let j = 0; j < ny; j++) {
        g.fillStyle = ramp(s.fractions[(i * ny + j) * nz + layer] / 255);
        g.fillRect(px(i), py(j + 1), px(i + 1) - px(i), py(j) - py(j + 1));
      }
    }
    g.strokeStyle = "#f79009";
    g.lineWidth = 1.5;
    for (const ring of s.outlines[k]) {
      g.beginPath();
      for (let m = 0; m + 1 < ring.length; m += 2) {
        g.lineTo(x0 + (ring[m] - s.origin[0]) * scale, y0 - (ring[m + 1] - s.origin[1]) * scale);
      }
      g.closePath();
      g.stroke();
    }
    canvas.setAttribute("data-layer", String(layer));
    canvas.setAttribute("data-cells", JSON.stringify({ x0, y0, sx: dx * scale, sy: dy * scale }));
  },
};

// A fraction's colour, as `meshvol grid --png` draws it: white at 0, dark blue at 1,
// dark red at -1 (inward-wound).
function ramp(f) {
  const t = Math.max(-1, Math.min(1, f)), a = Math.abs(t);
  const target = t >= 0 ? [24, 64, 160] : [170, 30, 30];
  return "rgb(" + target.map((c) => Math.round(255 + (c - 255) * a)).join(",") + ")";
}

// ---- the 3D view ----------------------------------------------------------------------
const COLORS = { solid: 0x9fb4c8, cap: 0xffc83d, hole: 0xff2020, nm: 0xe040fb, cross: 0xff8c00, cavity: 0x22c3e6 };
// Overlapping pairs' tints: none near the problems' red, orange, yellow, magenta, cyan.
const PAIR_TINTS = [0x7e57c2, 0x29a329, 0x3949ab, 0x8d6e63, 0x9e9d24, 0x00897b];

const viewer = {
  init() {
    const box = $("view");
    this.box = box;
    // The slider moves the section shown even where there is no 3D view to cut.
    $("clip").addEventListener("input", () => this.setClip());
    if (!window.THREE || !box) return;
    try {
      this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    } catch (e) {
      box.append(el("div", { class: "note" }, "no WebGL in this browser: the report is complete without the view"));
      return;
    }
    this.renderer.localClippingEnabled = true;
    this.renderer.setClearColor(0xffffff);
    box.append(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.controls = new THREE.OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener("change", () => this.render());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x667085, 0.9));
    const sun = new THREE.DirectionalLight(0xffffff, 0.6);
    sun.position.set(1, 2, 3);
    this.camera.add(sun);
    this.scene.add(this.camera);
    this.clip = new THREE.Plane(new THREE.Vector3(0, 0, -1), 1e30);
    this.group = null;
    new ResizeObserver(() => this.resize()).observe(box);
    $("reset-view").addEventListener("click", () => this.frame(null));
    this.resize();
  },
  resize() {
    if (!this.renderer) return;
    const w = this.box.clientWidth || 640, h = this.box.clientHeight || 480;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  },
  render() {
    if (this.renderer) this.renderer.render(this.scene, this.camera);
  },
  show(view) {
    this.view = view;
    if (!this.renderer) return;
    if (this.group) this.scene.remove(this.group);
    this.group = new THREE.Group();
    this.scene.add(this.group);
    const p = view.positions, t = view.triangles;
    const tint = new Map();
    view.overlapping_shells.forEach((pair, i) => pair.forEach((s) => { if (!tint.has(s)) tint.set(s, PAIR_TINTS[i % PAIR_TINTS.length]); }));
    const cavities = new Set(view.cavities);
    const n = t.length / 3;
    const pos = new Float32Array(n * 9), col = new Float32Array(n * 9);
    const c = new THREE.Color();
    for (let i = 0; i < n; i++) {
      const s = view.triangle_shells[i];
      c.setHex(i >= view.cap_start ? COLORS.cap : tint.has(s) ? tint.get(s) : cavities.has(s) ? COLORS.cavity : COLORS.solid);
      for (let k = 0; k < 3; k++) {
        const v = t[3 * i + k];
        pos.set([p[3 * v], p[3 * v + 1], p[3 * v + 2]], 9 * i + 3 * k);
        col.set([c.r, c.g, c.b], 9 * i + 3 * k);
      }
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(pos, 3));
    g.setAttribute("color", new THREE.BufferAttribute(col, 3));
    g.computeVertexNormals();
    const solid = new THREE.Mesh(g, new THREE.MeshLambertMaterial({
      vertexColors: THREE.VertexColors, side: THREE.DoubleSide, clippingPlanes: [this.clip],
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    }));
    this.group.add(solid);
    this.bounds = new THREE.Box3().setFromBufferAttribute(g.getAttribute("position"));
    this.lines(view.boundary_edges, COLORS.hole);
    this.lines(view.non_manifold_edges, COLORS.nm);
    for (const x of view.crossings) {
      const cg = new THREE.BufferGeometry();
      cg.setAttribute("position", new THREE.BufferAttribute(new Float32Array(x.triangles[0].concat(x.triangles[1])), 3));
      // Drawn over the solid's own copy of these faces (pushed back by its polygon offset).
      const m = new THREE.Mesh(cg, new THREE.MeshBasicMaterial({ color: COLORS.cross, side: THREE.DoubleSide, clippingPlanes: [this.clip] }));
      m.renderOrder = 2;
      this.group.add(m);
    }
    this.marker = null;
    $("clip").value = 1000;
    this.setClip();
    this.frame(null);
    this.box.setAttribute("data-drawn", "true");
    this.box.setAttribute("data-triangles", String(n));
    this.box.setAttribute("data-boundary-edges", String(view.boundary_edges.length / 2));
  },
  // Edges (vertex id pairs) as lines drawn over the solid, so a rim shows through it.
  lines(ids, color) {
    if (!ids.length) return;
    const p = this.view.positions, pos = new Float32Array(ids.length * 3);
    ids.forEach((v, i) => pos.set([p[3 * v], p[3 * v + 1], p[3 * v + 2]], 3 * i));
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.BufferAttribute(pos, 3));
    const l = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color, depthTest: false }));
    l.renderOrder = 3;
    this.group.add(l);
  },
  setClip() {
    const f = $("clip").value / 1000;
    const k = slices.s ? slices.level(f) : -1;
    // The profile's level at the section's (the middle of its layer, (k + ½) / n: the
    // profile has two levels a layer).
    profile.at(k >= 0 && f < 1 ? (k + 0.5) / slices.s.levels.length : f);
    slices.at(k);
    if (!this.bounds || this.bounds.isEmpty()) return;
    // With sections, the cut snaps to the level of the section shown.
    const z = k >= 0 ? slices.s.levels[k] : this.bounds.min.z + f * (this.bounds.max.z - this.bounds.min.z);
    this.clip.constant = f >= 1 ? 1e30 : z;
    $("clip-level").textContent = f >= 1 ? "off" : "z ≤ " + fmt(z, 5);
    this.render();
  },
  // Frames `target` (edges, coordinates or shells; null: the whole part), boxed.
  frame(target) {
    if (!this.renderer || !this.bounds) return;
    const box = new THREE.Box3();
    const p = this.view.positions;
    const addVertex = (v) => box.expandByPoint(new THREE.Vector3(p[3 * v], p[3 * v + 1], p[3 * v + 2]));
    if (!target) box.copy(this.bounds);
    else if (target.edges) target.edges.forEach(([a, b]) => { addVertex(a); addVertex(b); });
    else if (target.coords) for (let i = 0; i + 2 < target.coords.length; i += 3) box.expandByPoint(new THREE.Vector3(target.coords[i], target.coords[i + 1], target.coords[i + 2]));
    else if (target.shells) {
      const want = new Set(target.shells), t = this.view.triangles;
      this.view.triangle_shells.forEach((s, i) => { if (want.has(s)) for (let k = 0; k < 3; k++) addVertex(t[3 * i + k]); });
    }
    if (box.isEmpty()) box.copy(this.bounds);
    if (this.marker) this.scene.remove(this.marker);
    this.marker = target ? new THREE.Box3Helper(box.clone().expandByScalar(1e-3 * this.bounds.getSize(new THREE.Vector3()).length()), 0x2e90fa) : null;
    if (this.marker) this.scene.add(this.marker);
    if (target && target.clip) {
      const c = box.getCenter(new THREE.Vector3());
      const span = this.bounds.max.z - this.bounds.min.z;
      $("clip").value = span > 0 ? Math.round(1000 * (c.z - this.bounds.min.z) / span) : 1000;
      this.setClip();
    }
    const centre = box.getCenter(new THREE.Vector3());
    const whole = this.bounds.getSize(new THREE.Vector3()).length() || 1;
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, whole * 0.02);
    const distance = radius / Math.sin((this.camera.fov * Math.PI) / 360) * 1.1;
    const dir = target ? this.camera.position.clone().sub(this.controls.target).normalize() : new THREE.Vector3(1, -1.4, 0.9).normalize();
    if (dir.lengthSq() === 0) dir.set(1, -1.4, 0.9).normalize();
    this.camera.up.set(0, 0, 1);
    this.camera.near = distance / 1000;
    this.camera.far = distance * 10 + whole * 4;
    this.camera.updateProjectionMatrix();
    this.camera.position.copy(centre).addScaledVector(dir, distance);
    this.controls.target.copy(centre);
    this.controls.update();
    this.render();
  },
};

// ---- start ------------------------------------------------------------------------------
function start() {
  viewer.init();
  if (window.MESHVOL_PAGE) {
    $("inputs").hidden = true;
    const page = window.MESHVOL_PAGE;
    const card = addCard({ name: page.check.file || "mesh" });
    fillCard(card, { name: page.check.file || "mesh", page });
    return;
  }
  const drop = $("drop");
  $("files").addEventListener("change", (e) => { sendAll([...e.target.files]); e.target.value = ""; });
  ["dragenter", "dragover"].forEach((k) => drop.addEventListener(k, (e) => { e.preventDefault(); drop.classList.add("over"); }));
  ["dragleave", "drop"].forEach((k) => drop.addEventListener(k, (e) => { e.preventDefault(); drop.classList.remove("over"); }));
  drop.addEventListener("drop", (e) => sendAll([...e.dataTransfer.files]));
  $("material").addEventListener("change", (e) => { $("density").value = e.target.value; });
  fetch("/api/limits").then((r) => r.json()).then((l) => {
    window.MESHVOL_LIMITS = l;
    $("limits").textContent = `Up to ${(l.max_upload / 1048576).toFixed(0)} MiB a file; files are measured in memory and not kept.`;
  }).catch(() => {});
}
if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start); else start();
