// linkwork viewer: the mechanism, its plans and charts over a precomputed cycle.
//
// Drawing transform of the scheme: SVG user units are millimetres, x to the right and y down, so a
// point at (x, y) metres is drawn at (1000 x, -1000 y).  The plans are drawn in millimetres of the
// sheet: a plan vector u is drawn u / scale mm long (scale in units per mm, data-scale on the svg),
// with y flipped the same way.  Everything comes from one payload (GET api/cycle, POST api/solve, or
// the data embedded by linkwork view --export), turned into a model of typed arrays; an edit's compact
// answer (POST api/edit) is merged into it.  Moving the crank only indexes its arrays.
//
// This file is the core (the model, the scheme, the plans, the charts, the structure, the crank);
// forces.js draws the forces on the scheme, forceplans.js the force plans and Zhukovsky's lever, and
// editing.js the edits (the panel, dragging, undo, saving), each through the hooks of window.linkworkViewer.
"use strict";

(function () {
  const NS = "http://www.w3.org/2000/svg";
  const state = {
    data: null, // the model shown
    full: null, // the model of the last whole payload (its labels placed): edits are merged into it
    base: null, // the model of the mechanism as loaded
    embedded: false,
    index: 0,
    playing: false,
    position: 0, // fractional sample while playing
    last: null,
    chosen: null, // keys of the charted series
    parts: {}, // by part of the page, the functions (i) -> void run on every change of the crank angle
    keys: {}, // by part, what it was built for
    chartUpdate: [],
    charts: [],
    hooks: { build: [], show: [], index: [] },
    updates: 0, // edits' answers shown
  };

  const $ = (id) => document.getElementById(id);

  function svg(tag, attrs, parent) {
    const e = document.createElementNS(NS, tag);
    for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (parent) parent.appendChild(e);
    return e;
  }

  // a label's text in an SVG text element, its subscripts (the scene's rule, the payload's pattern:
  // "n_ba", "O1") smaller and lowered in tspans, so that no label shows a raw underscore
  function setLabel(t, text) {
    if (t.dataset.text === text) return;
    t.dataset.text = text;
    t.replaceChildren();
    const pattern = state.full && state.full.scene.subscripts;
    const re = pattern ? new RegExp(pattern, "gu") : null;
    let at = 0;
    for (const m of re ? text.matchAll(re) : []) {
      const base = m[1] !== undefined ? m[1] : m[3], sub = m[1] !== undefined ? m[2] : m[4];
      t.appendChild(document.createTextNode(text.slice(at, m.index) + base));
      svg("tspan", { "baseline-shift": "sub", "font-size": "70%", class: "sub" }, t).textContent = sub;
      at = m.index + m[0].length;
    }
    if (at < text.length) t.appendChild(document.createTextNode(text.slice(at)));
  }

  function html(tag, text, parent, attrs) {
    const e = document.createElement(tag);
    if (text !== undefined && text !== null) e.textContent = text;
    for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
    if (parent) parent.appendChild(e);
    return e;
  }

  // the page's texts in its language: the payload's ``texts`` (linkwork.lang's catalogues, key -> text), the
  // fields in braces filled from ``fields`` (a doubled brace is the brace itself)
  function T(key, fields) {
    const text = ((state.full || state.base || {}).texts || {})[key];
    if (text === undefined) return key;
    return text.replace(/\{\{|\}\}|\{(\w+)\}/g, (m, name) => {
      if (!name) return m[0];
      return fields && fields[name] !== undefined && fields[name] !== null ? String(fields[name]) : m;
    });
  }

  const russian = () => ((state.full || state.base || {}).lang || "en") === "ru";
  const POWER = { "-": "⁻", 0: "⁰", 1: "¹", 2: "²", 3: "³", 4: "⁴", 5: "⁵", 6: "⁶", 7: "⁷", 8: "⁸", 9: "⁹" };

  // a number written as the page's language writes it (linkwork.lang.russian_numbers): in Russian a decimal
  // comma, and a power of ten for an exponent (2.5e+5 as 2,5·10⁵)
  function written(text) {
    text = String(text);
    if (!russian()) return text;
    const m = /^(-?[0-9.]+)e([-+]?[0-9]+)$/.exec(text);
    if (m) return m[1].replace(".", ",") + "·10" + String(Number(m[2])).replace(/./g, (c) => POWER[c]);
    return text.replace(".", ",");
  }

  // ``v`` with ``digits`` decimals, as the page's language writes it
  const fixed = (v, digits) => written(Number(v).toFixed(digits));

  // items of a list: "a 1.5, b 2" in English, "a 1,5; b 2" in Russian (its decimal commas stay apart)
  const listed = (items) => items.join(russian() ? "; " : ", ");

  // a name in runs (linkwork.web.force_plans.tex_runs: [text, "" | "sub" | "sup"]) into an SVG text, its subscripts
  // and superscripts smaller in tspans; into an HTML element as <sub> and <sup>
  function setRuns(t, runs) {
    t.replaceChildren();
    const inSvg = t.namespaceURI === NS;
    for (const [text, kind] of runs) {
      if (!kind) t.appendChild(document.createTextNode(text));
      else if (inSvg) svg("tspan", { "baseline-shift": kind === "sub" ? "sub" : "super", "font-size": "70%", class: kind }, t).textContent = text;
      else html(kind, text, t);
    }
  }

  const X = (p) => (1000 * p[0]).toFixed(4);
  const Y = (p) => (-1000 * p[1]).toFixed(4);
  function fmt(v, digits) {
    if (v === null || v === undefined || !isFinite(v)) return "-";
    const a = Math.abs(v);
    if (a !== 0 && (a >= 1e6 || a < 1e-3)) return written(Number(v).toExponential((digits || 4) - 1));
    return written(String(Number(Number(v).toPrecision(digits || 4))));
  }

  // ------------------------------------------------------------------ the model

  // An array of any rank as flat numbers and a shape; NaN where the payload has null.
  class Grid {
    constructor(data, shape) { this.data = data; this.shape = shape; }
    static nested(list, rank) {
      const shape = [];
      let x = list;
      for (let r = 0; r < rank; r++) { shape.push(x ? x.length : 0); x = x && x.length ? x[0] : null; }
      const data = new Float64Array(shape.reduce((a, b) => a * b, 1));
      let k = 0;
      const walk = (v, r) => {
        if (r === rank) { data[k++] = v === null ? NaN : v; return; }
        for (let i = 0; i < shape[r]; i++) walk(v === null ? null : v[i], r + 1);
      };
      walk(list, 0);
      return new Grid(data, shape);
    }
    static of(x, rank) { return x instanceof Grid ? x : Grid.nested(x, rank); }
    // the vector of the last axis at leading indices (i, j): an array, or null where it is NaN
    at(i, j) {
      const sh = this.shape, d = this.data, n = sh[sh.length - 1];
      const k = (sh.length === 3 ? i * sh[1] + j : i) * n;
      const x = d[k];
      if (x !== x) return null; // NaN
      return n === 2 ? [x, d[k + 1]] : n === 3 ? [x, d[k + 1], d[k + 2]] : Array.from(d.subarray(k, k + n));
    }
    list() { return Array.from(this.data, (v) => (isNaN(v) ? null : v)); }
  }

  // an edit's answer (linkwork.web.update.encode_edit): the length of its JSON (uint32, little-endian), the
  // JSON, zero bytes up to a multiple of 8, then its arrays' bytes; each array {dtype, shape, offset} in the
  // JSON becomes a Grid over its bytes where they lie
  const TYPES = { f4: Float32Array, f8: Float64Array, u1: Uint8Array };
  function readEdit(buf) {
    const n = new DataView(buf).getUint32(0, true);
    const base = 4 + n + ((8 - ((4 + n) % 8)) % 8);
    return JSON.parse(new TextDecoder().decode(new Uint8Array(buf, 4, n)), (key, v) => {
      if (!v || typeof v !== "object" || v.offset === undefined || !TYPES[v.dtype] || !v.shape) return v;
      return new Grid(new TYPES[v.dtype](buf, base + v.offset, v.shape.reduce((a, b) => a * b, 1)), v.shape);
    });
  }

  function place(pose, xy) {
    const c = Math.cos(pose[2]), s = Math.sin(pose[2]);
    return [pose[0] + c * xy[0] - s * xy[1], pose[1] + s * xy[0] + c * xy[1]];
  }

  // the model of a whole payload
  function model(d) {
    const scene = d.scene;
    const m = Object.assign({}, d);
    m.steps = d.angles_deg.length;
    m.positions = Grid.of(d.positions, 3);
    m.poses = Grid.of(scene.poses, 3);
    m.plans = {};
    for (const kind in d.plans) m.plans[kind] = Object.assign({}, d.plans[kind], { values: Grid.of(d.plans[kind].values, 3) });
    m.scene = Object.assign({}, scene, { plans: {} });
    m.scene.labels = scene.labels.map((lab) => Object.assign({}, lab, { centre: Grid.of(lab.centre, 2) }));
    for (const kind in scene.plans) {
      m.scene.plans[kind] = Object.assign({}, scene.plans[kind], { centres: Grid.of(scene.plans[kind].centres, 3) });
    }
    if (d.forces && d.forces.values) m.forces = Object.assign({}, d.forces, { values: Grid.of(d.forces.values, 3) });
    return m;
  }

  // an edit's answer merged into the model of the last whole payload: the labels move with what they name
  function merge(full, ans) {
    const m = Object.assign({}, full, {
      overrides: ans.overrides, parameters: ans.parameters, events: ans.events, warnings: ans.warnings,
      local: ans.local, extremes: ans.extremes || full.extremes, stale: ans.extremes ? null : "extremes",
      peaks: ans.peaks || full.peaks,
    });
    m.valid = Array.from(Grid.of(ans.valid, 1).data, (v) => Boolean(v));
    m.poses = Grid.of(ans.scene.poses, 3);
    m.positions = positionsOf(m);
    m.plans = {};
    m.scene = Object.assign({}, full.scene, {
      size: ans.scene.size, r: ans.scene.r, em: ans.scene.em, items: itemsOf(ans.scene.item_table), plans: {},
      elements: ans.scene.elements || full.scene.elements || [],
    });
    m.scene.labels = full.scene.labels.map((lab, k) => Object.assign({}, lab, {
      at: ans.scene.label_at[k], centre: movedLabel(full, m, lab, ans.scene.label_at[k]),
    }));
    for (const kind in full.plans) {
      const old = full.plans[kind];
      const plan = Object.assign({}, old, { scale_per_mm: ans.plans[kind].scale_per_mm, values: Grid.of(ans.plans[kind].values, 3) });
      m.plans[kind] = plan;
      const look = Object.assign({}, full.scene.plans[kind], ans.scene.plans[kind]);
      look.centres = movedPlanLabels(old, plan, full.scene.plans[kind].centres);
      m.scene.plans[kind] = look;
    }
    const values = Grid.of(ans.series.values, 2);
    const n = m.steps;
    m.series = full.series.map((s) => {
      const k = ans.series.keys.indexOf(s.key);
      if (k < 0) return Object.assign({}, s, { values: new Array(n).fill(null) });
      return Object.assign({}, s, { values: Array.from(values.data.subarray(k * n, (k + 1) * n), (v) => (isNaN(v) ? null : v)) });
    });
    m.forces = Object.assign({}, ans.forces);
    if (ans.forces.values) m.forces.values = Grid.of(ans.forces.values, 3);
    return m;
  }

  // the scheme's items of an edit's answer, from its table (linkwork.web.update.item_table): one object an item,
  // as the whole payload gives them
  function itemsOf(t) {
    const xy = t.xy.data;
    let start = 0;
    return t.kind.map((kind, k) => {
      const end = t.ends[k], pts = [];
      for (let j = start; j < end; j++) pts.push([xy[2 * j], xy[2 * j + 1]]);
      start = end;
      return { kind, link: t.link[k], name: t.name[k], closed: t.closed[k], radius: t.radius[k], xy: pts };
    });
  }

  // every point at every sample from the links' poses and the points in their links' axes
  function positionsOf(m) {
    const n = m.steps, P = m.points.length, N = m.poses.shape[1], q = m.poses.data;
    const data = new Float64Array(n * P * 2).fill(NaN);
    for (let p = 0; p < P; p++) {
      const link = m.points[p].link, [lx, ly] = m.local[p];
      for (let i = 0; i < n; i++) {
        const k = (i * P + p) * 2;
        if (link === 0) { data[k] = lx; data[k + 1] = ly; continue; }
        if (!m.valid[i]) continue;
        const b = (i * N + link) * 3, c = Math.cos(q[b + 2]), s = Math.sin(q[b + 2]);
        data[k] = q[b] + c * lx - s * ly; data[k + 1] = q[b + 1] + s * lx + c * ly;
      }
    }
    return new Grid(data, [n, P, 2]);
  }

  // a label's centres, moved as its anchor moves from the placed model to the edited one
  function movedLabel(full, m, lab, at) {
    const n = m.steps, out = new Float64Array(2 * n).fill(NaN);
    const anchor = (mod, i, xy) => {
      if (lab.link === 0) return xy;
      const pose = mod.valid[i] ? mod.poses.at(i, lab.link) : null;
      return pose ? place(pose, xy) : null;
    };
    let fallback = null;
    for (let i = 0; i < n && !fallback; i++) {
      const c = lab.centre.at(i, 0), a = anchor(full, i, lab.at);
      if (c && a) fallback = [c[0] - a[0], c[1] - a[1]];
    }
    for (let i = 0; i < n; i++) {
      const a = anchor(m, i, at);
      if (!a) continue;
      const c = lab.centre.at(i, 0), a0 = anchor(full, i, lab.at);
      const off = c && a0 ? [c[0] - a0[0], c[1] - a0[1]] : fallback || [m.scene.em, m.scene.em];
      out[2 * i] = a[0] + off[0]; out[2 * i + 1] = a[1] + off[1];
    }
    return new Grid(out, [n, 2]);
  }

  function movedPlanLabels(old, plan, centres) {
    const [n, L] = centres.shape;
    const out = new Float64Array(n * L * 2).fill(NaN);
    for (let i = 0; i < n; i++) {
      for (let j = 0; j < L; j++) {
        const c = centres.at(i, j), v0 = old.values.at(i, j), v = plan.values.at(i, j);
        if (!c || !v0 || !v) continue;
        const k = (i * L + j) * 2;
        out[k] = v[0] / plan.scale_per_mm + c[0] - v0[0] / old.scale_per_mm;
        out[k + 1] = v[1] / plan.scale_per_mm + c[1] - v0[1] / old.scale_per_mm;
      }
    }
    return new Grid(out, [n, L, 2]);
  }

  // ------------------------------------------------------------------ loading

  async function start() {
    bindControls();
    const node = $("linkwork-data");
    if (node && node.textContent.trim()) {
      state.embedded = true;
      load(JSON.parse(node.textContent));
      return;
    }
    try {
      // first the cycle with its labels placed at the position shown (at once), then placed along the cycle
      const r = await fetch("api/cycle?labels=first", { headers: { Accept: "application/json" } });
      const body = await r.json();
      if (!r.ok) throw new Error(body.error || r.statusText);
      load(body);
      if (body.labels_placed < body.steps) placed();
    } catch (err) {
      showError(String(err.message || err));
    }
  }

  // the mechanism as loaded with its labels placed along the cycle: shown where the page still shows it
  async function placed() {
    try {
      const r = await fetch("api/cycle", { headers: { Accept: "application/json" } });
      if (!r.ok) return;
      const m = model(await r.json());
      const shown = state.data === state.base;
      if (state.full === state.base) state.full = m;
      state.base = m;
      if (shown) show(m);
    } catch (err) {
      // the server went away: the labels stay where they are
    }
  }

  // a mechanism's whole payload, as loaded: the page is built for it
  function load(data) {
    const m = model(data);
    state.base = state.full = m;
    $("loading").hidden = true;
    document.title = m.name + ": " + T("view.title");
    if (russian()) for (const o of document.querySelectorAll("#speed option, #force-zoom option")) o.textContent = written(o.textContent);
    $("title").textContent = m.name;
    $("formula").textContent = m.structure.formula;
    buildChoice(m);
    fit(m.scene);
    for (const f of state.hooks.build) f(m);
    show(m);
  }

  // a model on the page; ``edited``: an edit's answer (merged), else a whole payload
  function show(m, edited) {
    state.data = m;
    if (!edited) state.full = m;
    else state.updates += 1;
    const n = m.steps;
    $("angle").max = String(n - 1);
    state.index = Math.min(state.index, n - 1);
    // each part is built again only where what it draws changed (an edit changes the values, seldom the parts)
    drawn("scheme", schemeKey(m), () => buildScheme(m), () => refreshScheme(m));
    for (const kind of ["velocity", "acceleration"]) drawn(kind, planKey(m, kind), () => buildPlan(m, kind), () => refreshPlan(m, kind));
    drawCharts(m);
    buildStructure(m);
    for (const f of state.hooks.show) f(m, edited);
    $("scheme").setAttribute("data-updates", String(state.updates));
    // the labels as the scene placed them, or moved with their points since (an edit's answer)
    $("scheme").setAttribute("data-labels", edited ? "moved" : "placed");
    $("scheme").setAttribute("data-labels-placed", String(m.labels_placed));
    setIndex(state.index);
  }

  // build a part of the page where its key changed, else refresh it; its functions (i) -> void of the crank
  // angle are state.parts[name], built with it
  function drawn(name, key, build, refresh) {
    if (state.keys[name] !== key) {
      state.keys[name] = key;
      state.parts[name] = [];
      build();
    } else refresh();
  }

  // ------------------------------------------------------------------ the scheme

  // The drawing comes whole from the payload's scene (linkwork.scene, the one the figures and DXF draw):
  // items in the axes of their links, placed at the links' poses of the sample shown; labels where the
  // scene placed them.  Items of the frame (link 0) are drawn once.
  const GROUP = { path: "paths", hatch: "ground", support: "ground", guide: "ground" };
  const CLASS = { pivot: "joint" };

  // the view of the scheme: the scene's extent, two pivots' radii around it
  function fit(scene) {
    const [x0, y0, x1, y1] = scene.extent;
    const pad = 2000 * scene.r;
    state.view = [1000 * x0 - pad, -1000 * y1 - pad, 1000 * (x1 - x0) + 2 * pad, 1000 * (y1 - y0) + 2 * pad];
    const root = $("scheme");
    root.setAttribute("viewBox", state.view.map((v) => v.toFixed(3)).join(" "));
    root.setAttribute("preserveAspectRatio", "xMidYMid meet");
    root.setAttribute("data-transform", "x_svg = 1000 x, y_svg = -1000 y (mm, x and y in m)");
  }

  // the view grown to hold the scene's extent (never shrunk under the pointer)
  function grow(scene) {
    const [x, y, w, h] = state.view;
    const old = [x, y, x + w, y + h];
    fit(scene);
    const [a, b, c, d] = state.view;
    const box = [Math.min(old[0], a), Math.min(old[1], b), Math.max(old[2], a + c), Math.max(old[3], b + d)];
    state.view = [box[0], box[1], box[2] - box[0], box[3] - box[1]];
    $("scheme").setAttribute("viewBox", state.view.map((v) => v.toFixed(3)).join(" "));
  }

  // what the scheme's elements are: the items (not where their vertices are), the labels, the trajectories
  function schemeKey(m) {
    const items = m.scene.items.map((it) => [it.kind, it.link, it.name, it.closed, it.radius > 0, it.xy.length].join("/"));
    const elements = (m.scene.elements || []).map((e) => [e.kind, e.name, e.strokes.length].join("/"));
    return JSON.stringify([m.name, items, elements, m.scene.labels.length, m.scene.paths]);
  }

  function buildScheme(m) {
    const root = $("scheme");
    let drawing = $("drawing");
    if (!drawing) drawing = svg("g", { id: "drawing" }, root);
    drawing.replaceChildren();
    root.insertBefore(drawing, root.firstChild);
    const scene = m.scene, update = state.parts.scheme;
    const groups = {};
    for (const id of ["paths", "ground", "links", "pairs", "labels"]) groups[id] = svg("g", { id: id }, drawing);
    state.trajectories = scene.paths.map((p) => [p, svg("path", { class: "path", "data-point": m.points[p].label }, groups.paths)]);
    state.fixed = [];
    state.circles = [];
    (scene.elements || []).forEach((element, k) => drawElement(k, element, groups.links));
    scene.items.forEach((item, k) => drawItem(k, item, groups[GROUP[item.kind] || (item.link === 0 || item.radius ? "pairs" : "links")]));
    scene.labels.forEach((lab, k) => {
      const t = svg("text", { class: lab.kind === "link" ? "link-number" : "label", "text-anchor": "middle", "dominant-baseline": "central" }, groups.labels);
      setLabel(t, lab.text);
      update.push((i) => {
        const c = state.data.scene.labels[k].centre.at(i, 0);
        if (!c) { t.setAttribute("visibility", "hidden"); return; }
        t.setAttribute("visibility", "visible");
        t.setAttribute("x", X(c)); t.setAttribute("y", Y(c));
      });
    });
    groups.paths.setAttribute("display", $("show-paths").checked ? "inline" : "none");
    refreshScheme(m);
  }

  // what an edit changes that no crank angle does: the trajectories, the frame's items, the sizes of the
  // pivots and of the text (they follow the drawing's size)
  function refreshScheme(m) {
    const pos = m.positions, P = pos.shape[1], d = pos.data;
    for (const [p, el] of state.trajectories) {
      const parts = [];
      let pen = false;
      for (let i = 0; i < m.steps; i++) {
        const k = (i * P + p) * 2, x = d[k];
        if (x !== x) { pen = false; continue; }
        parts.push((pen ? "L" : "M") + Math.round(1e5 * x) / 100 + "," + Math.round(-1e5 * d[k + 1]) / 100);
        pen = true;
      }
      el.setAttribute("d", parts.join(""));
    }
    for (const [k, put] of state.fixed) put(m.scene.items[k].xy);
    for (const [k, el] of state.circles) el.setAttribute("r", (1000 * m.scene.items[k].radius).toFixed(4));
    $("labels").setAttribute("font-size", (1000 * m.scene.em).toFixed(3));
  }

  // one item, the k-th of the scene: a circle (pivot, marker), an outline (polygon), a line or a polyline
  function drawItem(k, item, g) {
    const cls = CLASS[item.kind] || item.kind;
    const attrs = { class: cls };
    if (item.kind === "bar" || item.kind === "plate") attrs["data-link"] = item.name;
    else if (item.radius) { attrs["data-point"] = item.name.split(".").pop(); attrs["data-joint"] = item.name; }
    else attrs["data-joint"] = item.name;
    const tag = item.radius ? "circle" : item.closed ? "polygon" : item.xy.length === 2 ? "line" : "polyline";
    const e = svg(tag, attrs, g);
    if (item.radius) state.circles.push([k, e]);
    const put = (xy) => {
      if (!xy) { e.setAttribute("visibility", "hidden"); return; }
      e.setAttribute("visibility", "visible");
      if (item.radius) { e.setAttribute("cx", X(xy[0])); e.setAttribute("cy", Y(xy[0])); }
      else if (tag === "line") {
        e.setAttribute("x1", X(xy[0])); e.setAttribute("y1", Y(xy[0]));
        e.setAttribute("x2", X(xy[1])); e.setAttribute("y2", Y(xy[1]));
      } else e.setAttribute("points", xy.map((v) => X(v) + "," + Y(v)).join(" "));
    };
    if (item.link === 0) { state.fixed.push([k, put]); return; }
    state.parts.scheme.push((i) => {
      const m = state.data, pose = m.valid[i] ? m.poses.at(i, item.link) : null;
      put(pose ? m.scene.items[k].xy.map((v) => place(pose, v)) : null);
    });
  }

  // a spring or a damper, the k-th of the scene's elements: a polyline for each stroke of its symbol, rows
  // (f, s, c) laid between its two points a and b at the sample shown (a + f (b - a) + s u + c n,
  // linkwork.scene.SchemeScene.element_strokes)
  function drawElement(k, element, g) {
    const lines = element.strokes.map(() => svg("polyline", { class: element.kind, "data-element": element.name }, g));
    state.parts.scheme.push((i) => {
      const m = state.data, e = m.scene.elements[k];
      const ends = m.valid[i] ? e.links.map((link, j) => place(m.poses.at(i, link), e.at[j])) : null;
      const d = ends ? [ends[1][0] - ends[0][0], ends[1][1] - ends[0][1]] : null;
      const len = d ? Math.hypot(d[0], d[1]) : 0;
      lines.forEach((line, j) => {
        if (!(len > 0)) { line.setAttribute("visibility", "hidden"); return; }
        const u = [d[0] / len, d[1] / len], a = ends[0];
        const xy = e.strokes[j].map(([f, s, c]) => [a[0] + f * d[0] + s * u[0] - c * u[1], a[1] + f * d[1] + s * u[1] + c * u[0]]);
        line.setAttribute("visibility", "visible");
        line.setAttribute("points", xy.map((v) => X(v) + "," + Y(v)).join(" "));
      });
    });
  }

  // ------------------------------------------------------------------ the plans

  const KINDS = ["absolute", "rotation", "normal", "tangential", "transport", "coriolis", "sliding"];

  // what a plan's elements are: its points and vectors, its frame and the size of its labels
  function planKey(m, kind) {
    const look = m.scene.plans[kind], plan = m.plans[kind];
    return JSON.stringify([m.name, look.frame, look.em, look.kinds, plan.labels, plan.vectors.length]);
  }

  // the plan's scale may change with an edit: its elements read it, and the model, when they are placed
  function refreshPlan(m, kind) {
    $(kind + "-plan").setAttribute("data-scale", String(m.plans[kind].scale_per_mm));
  }

  function buildPlan(m, kind) {
    const root = $(kind + "-plan");
    root.replaceChildren();
    const plan = m.plans[kind];
    const look = m.scene.plans[kind];
    refreshPlan(m, kind);
    root.setAttribute("data-transform", "x_svg = u_x / scale, y_svg = -u_y / scale (mm of the drawing)");
    // one frame for the whole cycle, so that the plan does not jump while the crank turns (the scene's:
    // it holds the plans of 95 % of the positions; near a dead point accelerations grow without bound)
    const [x0, y0, x1, y1] = look.frame;
    const size = Math.max(x1 - x0, y1 - y0, 1e-9);
    const pad = 0.1 * size + 3 * look.em; // the labels beside the frame's outermost points stay in the panel
    root.setAttribute("viewBox", [x0 - pad, -y1 - pad, x1 - x0 + 2 * pad, y1 - y0 + 2 * pad].map((v) => v.toFixed(3)).join(" "));
    const defs = svg("defs", {}, root);
    for (const k of KINDS) {
      const mk = svg("marker", { id: `${kind}-head-${k}`, viewBox: "0 0 10 10", refX: "10", refY: "5", orient: "auto-start-reverse", markerUnits: "userSpaceOnUse" }, defs);
      mk.setAttribute("markerWidth", (0.03 * size).toFixed(3));
      mk.setAttribute("markerHeight", (0.03 * size).toFixed(3));
      svg("path", { d: "M0,0 L10,5 L0,10 z", class: "head " + k }, mk);
    }
    const grid = svg("g", {}, root);
    svg("line", { class: "grid", x1: x0 - pad, y1: 0, x2: x1 + pad, y2: 0 }, grid);
    svg("line", { class: "grid", x1: 0, y1: -y1 - pad, x2: 0, y2: -y0 + pad }, grid);
    const lines = svg("g", {}, root);
    const dots = svg("g", { "font-size": look.em.toFixed(3) }, root);
    const at = (now, i, j) => {
      const v = state.data.valid[i] ? now.values.at(i, j) : null;
      return v ? [v[0] / now.scale_per_mm, -v[1] / now.scale_per_mm] : null;
    };
    const pole = plan.labels.indexOf("p"); // the pole's point (its letter on the plan: look.pole, π on a Russian acceleration plan)
    const drawn = [];
    for (const j of plan.absolute) drawn.push({ from: pole, to: j, kind: "absolute" });
    for (const v of plan.vectors) drawn.push(v);
    const els = drawn.map((v) => svg("line", {
      class: "vec " + v.kind, "data-kind": v.kind, "data-from": plan.labels[v.from], "data-to": plan.labels[v.to],
      "marker-end": `url(#${kind}-head-${KINDS.includes(v.kind) ? v.kind : "rotation"})`,
    }, lines));
    const marks = plan.labels.map((lab, j) => {
      const c = svg("circle", { class: "dot", r: (0.012 * size).toFixed(4), "data-label": lab }, dots);
      const main = j === pole || plan.absolute.includes(j); // a point of the mechanism, not of the construction
      const t = svg("text", { class: main ? "plabel" : "plabel minor", "text-anchor": "middle", "dominant-baseline": "central" }, dots);
      return [c, t];
    });
    legend(root, kind, look.kinds);
    const caption = $(kind + "-caption");
    const unit = T(`plan.unit.${kind}`);
    const mu = kind === "velocity" ? "μv" : "μa";
    const units = T(kind === "velocity" ? "view.unit.m_s" : "view.unit.m_s2");
    state.parts[kind].push((i) => {
      const now = state.data.plans[kind], shown = state.data.scene.plans[kind];
      drawn.forEach((v, k) => {
        const a = at(now, i, v.from), b = at(now, i, v.to), e = els[k];
        const zero = a && b && Math.hypot(b[0] - a[0], b[1] - a[1]) < 1e-9 * size;
        if (!a || !b || zero) { e.setAttribute("visibility", "hidden"); return; }
        e.setAttribute("visibility", "visible");
        e.setAttribute("x1", a[0].toFixed(4)); e.setAttribute("y1", a[1].toFixed(4));
        e.setAttribute("x2", b[0].toFixed(4)); e.setAttribute("y2", b[1].toFixed(4));
      });
      plan.labels.forEach((lab, j) => {
        const p = at(now, i, j), [c, t] = marks[j];
        const text = shown.text[i][j], centre = shown.centres.at(i, j);
        if (!p) { c.setAttribute("visibility", "hidden"); t.setAttribute("visibility", "hidden"); return; }
        c.setAttribute("visibility", "visible");
        c.setAttribute("cx", p[0].toFixed(4)); c.setAttribute("cy", p[1].toFixed(4));
        // points that coincide share one label, the scene's (e.g. "e, knife_upper.edge")
        if (!text || !centre) { t.setAttribute("visibility", "hidden"); return; }
        t.setAttribute("visibility", "visible");
        setLabel(t, text);
        t.setAttribute("x", centre[0].toFixed(3)); t.setAttribute("y", (-centre[1]).toFixed(3));
      });
      const parts = plan.absolute.map((j) => {
        const v = state.data.valid[i] ? now.values.at(i, j) : null;
        return v ? `${plan.labels[j]} ${fmt(Math.hypot(v[0], v[1]), 3)}` : `${plan.labels[j]} -`;
      });
      caption.textContent = T("view.plan_caption", {
        plan: T(`plan.${kind}`), pole: look.pole || "p", mu, scale: written(now.scale_per_mm), unit,
        v: kind === "velocity" ? "v" : "a", units, values: listed(parts),
      });
    });
  }

  // the kinds of vector the plan draws over the cycle, each a short stroke in its style and its name
  function legend(root, kind, kinds) {
    const old = document.getElementById(kind + "-legend");
    if (old) old.remove();
    const box = html("div", null, null, { id: kind + "-legend", class: "legend" });
    root.parentNode.insertBefore(box, root.nextSibling);
    for (const k in kinds) {
      const item = html("span", null, box, { class: "legend-item" });
      const s = svg("svg", { width: "26", height: "8", viewBox: "0 0 26 8" }, item);
      svg("line", { class: "vec " + k, x1: 1, y1: 4, x2: 25, y2: 4 }, s);
      item.appendChild(document.createTextNode(" " + kinds[k]));
    }
  }

  // ------------------------------------------------------------------ charts

  function buildChoice(m) {
    const choice = $("series-choice");
    choice.replaceChildren();
    const keys = m.series.map((s) => s.key);
    if (!state.chosen || !state.chosen.some((k) => keys.includes(k))) {
      const want = ["torque", keys.find((k) => k.startsWith("slider:") && k.endsWith(":s")), "foundation:fy"];
      state.chosen = want.filter((k) => k && keys.includes(k));
      if (!state.chosen.length) state.chosen = keys.slice(0, 2);
    }
    for (const s of m.series) {
      const label = html("label", null, choice);
      const box = html("input", null, label, { type: "checkbox", "data-series": s.key });
      box.checked = state.chosen.includes(s.key);
      label.appendChild(document.createTextNode(` ${s.label}`));
      box.addEventListener("change", () => {
        state.chosen = Array.from(choice.querySelectorAll("input:checked")).map((b) => b.getAttribute("data-series"));
        drawCharts(state.data);
        setIndex(state.index);
      });
    }
  }

  function ticks(lo, hi, count) {
    const span = hi - lo || Math.abs(hi) || 1;
    const raw = span / count, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((f) => f * mag).find((s) => s >= raw);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step) out.push(Math.abs(v) < 1e-12 * span ? 0 : v);
    return out;
  }

  // a chart's viewBox (W x H) and the margins of its plot (left, right, top, bottom)
  const CHART = { W: 640, H: 150, L: 64, R: 12, T: 20, B: 22 };

  // the charts of the chosen series: built when the choice changes, their curves and axes redrawn per model
  function drawCharts(m) {
    const key = JSON.stringify([m.name, m.steps, state.chosen]);
    if (state.chartKey !== key) {
      state.chartKey = key;
      buildCharts(m);
    }
    for (const chart of state.charts) chart.refresh(m);
  }

  function buildCharts(m) {
    const root = $("charts");
    root.replaceChildren();
    state.chartUpdate = [];
    state.charts = [];
    for (const key of state.chosen) if (m.series.some((x) => x.key === key)) state.charts.push(chart(root, key));
    const note = html("div", T("view.chart_note"), root);
    note.className = "note";
  }

  function chart(root, key) {
    const { W, H, L, R, T: TOP, B } = CHART;
    const xOf = (i) => L + (W - L - R) * (state.data.turn_deg[i] / 360);
    const g = svg("svg", { class: "chart", viewBox: `0 0 ${W} ${H}`, preserveAspectRatio: "none", "data-series": key }, root);
    svg("line", { class: "axis", x1: L, y1: H - B, x2: W - R, y2: H - B }, g);
    svg("line", { class: "axis", x1: L, y1: TOP, x2: L, y2: H - B }, g);
    for (const t of [0, 90, 180, 270, 360]) {
      const x = L + (W - L - R) * t / 360;
      svg("text", { x: x, y: H - 6, "text-anchor": "middle" }, g).textContent = t + "°";
    }
    const axis = svg("g", {}, g), curve = svg("path", { class: "curve" }, g);
    const title = svg("text", { class: "title", x: L + 4, y: 13 }, g);
    const cursor = svg("line", { class: "cursor", y1: TOP, y2: H - B }, g);
    g.addEventListener("pointerdown", (ev) => pick(ev, g));
    g.addEventListener("pointermove", (ev) => { if (ev.buttons) pick(ev, g); });
    const out = { s: null };
    out.refresh = (m) => {
      const s = (out.s = m.series.find((x) => x.key === key));
      let lo = Infinity, hi = -Infinity;
      for (const v of s.values) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
      if (lo === Infinity) { lo = 0; hi = 1; }
      if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 1; hi += 1; }
      const yOf = (v) => TOP + (H - TOP - B) * (1 - (v - lo) / (hi - lo));
      g.setAttribute("data-lo", String(lo));
      g.setAttribute("data-hi", String(hi));
      g.setAttribute("data-transform", `x = ${L} + ${W - L - R} turn / 360, y = ${TOP} + ${H - TOP - B} (hi - v) / (hi - lo)`);
      axis.replaceChildren();
      if (lo < 0 && hi > 0) svg("line", { class: "zero", x1: L, y1: yOf(0), x2: W - R, y2: yOf(0) }, axis);
      for (const t of ticks(lo, hi, 3)) {
        const y = yOf(t);
        svg("line", { class: "axis", x1: L - 4, y1: y, x2: L, y2: y }, axis);
        svg("text", { x: L - 6, y: y + 4, "text-anchor": "end" }, axis).textContent = fmt(t, 3);
      }
      let d = "", pen = false;
      for (let i = 0; i < s.values.length; i++) {
        const v = s.values[i];
        if (v === null) { pen = false; continue; }
        d += (pen ? "L" : "M") + xOf(i).toFixed(2) + "," + yOf(v).toFixed(2);
        pen = true;
      }
      curve.setAttribute("d", d);
    };
    state.chartUpdate.push((i) => {
      const x = xOf(i).toFixed(2), s = out.s;
      cursor.setAttribute("x1", x); cursor.setAttribute("x2", x);
      cursor.setAttribute("data-index", String(i));
      title.textContent = T("view.chart_title", { label: s.label, unit: s.unit, value: fmt(s.values[i]), phi: fixed(state.data.turn_deg[i], 1) });
    });
    return out;
  }

  // the crank angle under the pointer: the pointer mapped into the chart's own coordinates by the SVG's
  // current geometry (whatever its size, padding or border), then the plot's x axis turned back into degrees
  function pick(ev, g) {
    const ctm = g.getScreenCTM();
    if (!ctm) return;
    const pt = g.createSVGPoint();
    pt.x = ev.clientX; pt.y = ev.clientY;
    const x = pt.matrixTransform(ctm.inverse()).x;
    const turn = ((x - CHART.L) / (CHART.W - CHART.L - CHART.R)) * 360;
    const turns = state.data.turn_deg;
    let best = 0;
    for (let i = 1; i < turns.length; i++) if (Math.abs(turns[i] - turn) < Math.abs(turns[best] - turn)) best = i;
    setIndex(best);
  }

  // ------------------------------------------------------------------ structure

  function buildStructure(m) {
    const root = $("structure");
    const said = JSON.stringify([m.name, m.structure.formula, m.extremes, m.peaks, m.stale, m.forces.checks, m.forces.available, m.events, m.warnings]);
    if (root.getAttribute("data-said") === said) return; // a drag changes none of it often
    root.setAttribute("data-said", said);
    root.replaceChildren();
    const s = m.structure;
    const tail = s.p4 ? `${russian() ? " − " : " - "}${s.p4}` : "";
    html("p", T("view.structure_line", { n: s.n_links, p5: s.p5, p4: s.p4, tail, dof: s.dof, q: s.redundant }), root);
    const drive = m.drives[0];
    html("p", T("view.drive", { joint: drive.joint, rpm: fmt(drive.rpm, 4), direction: T(`view.${drive.direction}`) }), root);
    table(root, ["#", T("view.head.group"), T("view.head.kind"), T("view.head.links"), T("view.head.joints")],
      s.groups.map((g, i) => [i + 1, g.formula_part, g.kind_shown || g.kind, g.link_names.join(", "), g.joints.join(", ")]));
    html("p", T("view.formula", { formula: s.formula }), root);
    if (m.extremes.length) {
      table(root, ["", T("view.head.stroke"), T("view.head.time_ratio"), T("view.head.forward")], m.extremes.map((e) => [
        `${T(`view.kind.${e.kind}`)} ${e.name}`,
        e.kind === "slider" ? `${fmt(1000 * e.stroke)} ${T("view.unit.mm")}` : `${fmt((e.stroke * 180) / Math.PI)}°`,
        fmt(e.time_ratio),
        fmt(e.forward_time_ratio),
      ])).setAttribute("id", "extremes");
      if (m.stale === "extremes") html("p", T("view.stale"), root, { class: "note" });
    }
    if (m.forces.available && m.forces.checks) {
      const c = m.forces.checks;
      html("p", T("view.checks", { power: fmt(c.driving_torque_vs_power_balance, 2), momentum: fmt(c.foundation_force_vs_momentum, 2), lever: fmt(c.driving_torque_vs_lever, 2) }), root);
    } else if (m.forces.available) {
      html("p", T("view.checks_later"), root);
    } else {
      html("p", T("view.no_forces", { reason: m.forces.reason }), root);
    }
    const peak = m.peaks && m.peaks.driving_torque;
    if (peak) { // refined between the samples: the number the command line, the report and the sweeps give
      const stale = m.stale === "extremes" ? T("view.before_drag") : "";
      html("p", T("view.peak", { value: fmt(peak.value, 6), phi: fixed(peak.turn_deg, 1), stale }), root, { id: "peak-torque" });
    }
    for (const e of m.events) html("p", e.text || `${e.kind}: ${e.message}`, root, { class: "warn" }); // text: in the page's language
    for (const w of m.warnings.concat(s.warnings || [])) html("p", w, root, { class: "warn" });
  }

  function table(parent, head, rows) {
    const t = html("table", null, parent);
    const tr = html("tr", null, html("thead", null, t));
    for (const h of head) html("th", h, tr);
    const body = html("tbody", null, t);
    for (const row of rows) {
      const r = html("tr", null, body);
      for (const c of row) html("td", String(c), r);
    }
    return t;
  }

  // ------------------------------------------------------------------ messages

  function showError(text) {
    $("error-text").textContent = text;
    $("error").hidden = false;
  }

  function hideError() {
    $("error").hidden = true;
    $("error-text").textContent = "";
  }

  // ------------------------------------------------------------------ the crank

  function setIndex(i) {
    const m = state.data;
    if (!m) return;
    const n = m.steps;
    i = ((Math.round(i) % n) + n) % n;
    state.index = i;
    const slider = $("angle");
    if (Number(slider.value) !== i) slider.value = String(i);
    for (const name in state.parts) for (const f of state.parts[name]) f(i);
    for (const f of state.chartUpdate) f(i);
    for (const f of state.hooks.index) f(i, m);
    const deg = m.angles_deg[i];
    const root = $("scheme");
    root.setAttribute("data-index", String(i));
    root.setAttribute("data-angle-deg", String(deg));
    $("angle-text").textContent = T("view.angle", { phi: fixed(m.turn_deg[i], 1), deg: fixed(((deg % 360) + 360) % 360, 1), i: i + 1, n });
    const note = $("pose-note");
    note.hidden = m.valid[i];
    note.textContent = m.valid[i] ? "" : T("view.no_pose");
  }

  function frame(t) {
    if (!state.playing) { state.last = null; return; }
    if (state.last !== null) {
      const n = state.data.steps;
      const period = state.data.period_s || 4;
      state.position = (state.position + ((t - state.last) / 1000) * Number($("speed").value) * n / period) % n;
      const i = Math.floor(state.position);
      if (i !== state.index) setIndex(i);
    }
    state.last = t;
    requestAnimationFrame(frame);
  }

  function play(on) {
    if (!state.data) return; // nothing to turn (nor the texts to say so) before the payload
    state.playing = on;
    $("play").textContent = T(on ? "view.pause" : "view.play");
    $("play").setAttribute("aria-pressed", String(on));
    if (on) { state.position = state.index; state.last = null; requestAnimationFrame(frame); }
  }

  function bindControls() {
    $("angle").addEventListener("input", (ev) => {
      setIndex(Number(ev.target.value));
      state.position = state.index;
    });
    $("play").addEventListener("click", () => play(!state.playing));
    $("show-paths").addEventListener("change", (ev) => {
      const g = $("paths");
      if (g) g.setAttribute("display", ev.target.checked ? "inline" : "none");
    });
    $("error-close").addEventListener("click", hideError);
    document.addEventListener("keydown", (ev) => {
      if (ev.target.tagName === "INPUT" || ev.target.tagName === "SELECT" || ev.ctrlKey || ev.metaKey) return;
      if (ev.key === " ") { ev.preventDefault(); play(!state.playing); }
      else if (ev.key === "ArrowRight" || ev.key === "ArrowLeft") {
        ev.preventDefault();
        setIndex(state.index + (ev.key === "ArrowRight" ? 1 : -1) * (ev.shiftKey ? 10 : 1));
        state.position = state.index;
      }
    });
  }

  window.linkworkViewer = {
    state, $, svg, html, fmt, T, written, fixed, listed, setRuns, setLabel, X, Y, place, Grid, readEdit, model, merge, show, load, grow, setIndex, showError, hideError,
    on: (name, f) => state.hooks[name].push(f),
  };

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
