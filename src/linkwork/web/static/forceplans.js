// linkwork viewer: the force plan of an Assur group, or Zhukovsky's lever, at the crank angle shown.
//
// The drawings are the scenes of linkwork.scene.force_plans, the ones the figures and DXF draw, as the payload
// gives them (linkwork.web.force_plans): arrows from start to end, their names where the scene placed them, the
// lever's lines and the lettered dots, in mm of the sheet with y up (drawn at (x, -y)).  The live page asks its
// server for the sample shown (POST api/force-plans, the latest wins, answers kept); an exported page carries
// some samples and shows the one nearest the crank.  Each drawing is fit to its panel (a force plan has a
// scale μF of its own at each position, stated in the caption).
"use strict";

(function () {
  const V = window.linkworkViewer;
  const { $, svg, html, fmt, T } = V;
  const F = { answers: new Map(), wanted: null, asking: false, shown: null };

  function part() { return V.state.data && V.state.data.force_plans; }

  function kN(v) { return Math.abs(v) >= 1000 ? `${fmt(v / 1000, 4)} ${T("unit.kN")}` : `${fmt(v, 4)} ${T("unit.N")}`; }

  // the text ``key`` into ``el``, its ``fields`` filled; a field given in ``lists`` is written "\u0001name\u0001"
  // in the fields and drawn as the arrows' names (their sub- and superscripts) with their forces
  const MARK = "\u0001";
  function say(el, key, fields, lists) {
    el.replaceChildren();
    T(key, fields).split(MARK).forEach((part, j) => {
      if (j % 2 === 0) { if (part) el.appendChild(document.createTextNode(part)); return; }
      lists[part].forEach((a, k) => {
        if (k) el.appendChild(document.createTextNode(V.listed(["", ""])));
        V.setRuns(html("span", null, el, { class: "fname", "data-name": a.text }), a.runs || [[a.text, ""]]);
        el.appendChild(document.createTextNode(` ${kN(a.value)}`));
      });
    });
  }
  const mark = (name) => MARK + name + MARK;

  // the group (or the lever) chosen, and the choice rebuilt where the mechanism's groups changed
  function choice(p) {
    const select = $("force-plan-choice");
    const key = JSON.stringify(p.groups.map((g) => g.key + g.title));
    if (select.getAttribute("data-groups") !== key) {
      const was = select.value;
      select.replaceChildren();
      for (const g of p.groups) html("option", g.title, select, { value: g.key });
      select.setAttribute("data-groups", key);
      if (p.groups.some((g) => g.key === was)) select.value = was;
    }
    return select.value;
  }

  // the drawings of sample i: the nearest an exported page carries, else the server's (asked for once)
  function wanted(i) {
    const m = V.state.data, p = part();
    if (p.samples.length || V.state.embedded) {
      let best = null;
      p.at.forEach((s, k) => {
        const d = Math.min(Math.abs(s.index - i), m.steps - Math.abs(s.index - i));
        if (best === null || d < best[0]) best = [d, k];
      });
      return best === null ? null : p.at[best[1]];
    }
    const key = JSON.stringify([m.overrides || {}, m.steps, i]);
    if (F.answers.has(key)) return F.answers.get(key);
    F.wanted = { key, body: { overrides: m.overrides || {}, steps: m.steps, index: i } };
    ask();
    return undefined;
  }

  // one question at a time; a newer one replaces the one waiting
  async function ask() {
    if (F.asking || !F.wanted) return;
    const { key, body } = F.wanted;
    F.asking = true;
    try {
      const r = await fetch("api/force-plans", {
        method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
      });
      const answer = await r.json();
      // a failure is kept as the answer too (said in the caption), so that it is not asked for again and again
      F.answers.set(key, r.ok ? answer.at[0] : { error: answer.error || r.statusText });
    } catch (err) {
      F.answers.set(key, { error: T("view.no_server") });
    }
    if (F.answers.size > 400) F.answers.delete(F.answers.keys().next().value);
    F.asking = false;
    if (F.wanted && F.wanted.key === key) F.wanted = null;
    if (F.wanted) ask();
    else update(V.state.index);
  }

  function update(i) {
    const p = part(), figure = $("force-plan-figure");
    figure.hidden = !p || !p.available;
    if (!p || !p.available) return;
    const key = choice(p);
    const sample = wanted(i);
    if (sample === undefined) return; // asked: drawn when the answer comes
    const k = p.groups.findIndex((g) => g.key === key);
    draw(p, sample, k);
  }

  function draw(p, sample, k) {
    const root = $("force-plan"), caption = $("force-plan-caption");
    const group = p.groups[k];
    const d = sample && sample.drawings[k];
    root.replaceChildren();
    root.setAttribute("data-group", group.key);
    if (sample && sample.error) {
      root.setAttribute("data-index", "");
      legend(p, null);
      caption.textContent = T("view.fp_error", { title: group.title, error: sample.error });
      return;
    }
    root.setAttribute("data-index", sample ? String(sample.index) : "");
    legend(p, d);
    if (!d || !d.arrows.length) {
      root.setAttribute("data-scale", "");
      caption.textContent = T(sample && !d ? "view.fp_no_pose" : "view.fp_dead", { title: group.title });
      return;
    }
    root.setAttribute("data-scale", String(d.scale));
    root.setAttribute("data-transform", "x_svg = x, y_svg = -y (mm of the drawing); an arrow of force F is |F| / scale mm long");
    const [x0, y0, x1, y1] = d.extent;
    const pad = 0.04 * Math.max(x1 - x0, y1 - y0) + 0.5 * d.em;
    root.setAttribute("viewBox", [x0 - pad, -y1 - pad, x1 - x0 + 2 * pad, y1 - y0 + 2 * pad].map((v) => v.toFixed(3)).join(" "));
    const defs = svg("defs", {}, root);
    const head = (0.55 * d.em).toFixed(3);
    for (const kind in p.styles) {
      const mk = svg("marker", { id: `fp-head-${kind}`, viewBox: "0 0 10 10", refX: "10", refY: "5", orient: "auto-start-reverse", markerUnits: "userSpaceOnUse", markerWidth: head, markerHeight: head }, defs);
      svg("path", { d: "M0,1 L10,5 L0,9 z", fill: p.styles[kind].colour }, mk);
    }
    const lines = svg("g", { class: "lever-lines" }, root);
    for (const [a, b] of d.lines) svg("line", { class: "lever-line", x1: a[0], y1: -a[1], x2: b[0], y2: -b[1], stroke: p.styles.lever.colour }, lines);
    const arrows = svg("g", { class: "force-arrows" }, root);
    const texts = svg("g", { class: "force-names", "font-size": d.em.toFixed(3) }, root);
    for (const a of d.arrows) {
      const style = p.styles[a.kind] || p.styles.reaction;
      const attrs = {
        class: "fvec " + a.kind + (a.resultant ? " resultant" : ""), "data-kind": a.kind, "data-name": a.text,
        "data-value": String(a.value), x1: a.start[0], y1: -a.start[1], x2: a.end[0], y2: -a.end[1], stroke: style.colour,
        "marker-end": `url(#fp-head-${p.styles[a.kind] ? a.kind : "reaction"})`,
      };
      if (a.resultant || style.dash.length) attrs["stroke-dasharray"] = "5 3";
      svg("line", attrs, arrows);
      if (a.text && a.centre && a.centre[0] !== null) {  // a name too long for its arrow is listed, not placed
        const t = svg("text", { class: "fname", fill: style.colour, x: a.centre[0].toFixed(3), y: (-a.centre[1]).toFixed(3), "text-anchor": "middle", "dominant-baseline": "central", "data-name": a.text }, texts);
        t.style.strokeWidth = (0.12 * d.em).toFixed(3); // the halo in the drawing's units, narrower than a stroke of a letter
        V.setRuns(t, a.runs || [[a.text, ""]]);
      }
    }
    d.dots.forEach((c, j) => {
      svg("circle", { class: "dot", cx: c[0], cy: -c[1], r: (0.12 * d.em).toFixed(3), "data-label": d.dot_text[j] }, texts);
      const at = d.dot_centres[j];
      if (d.dot_text[j] && at && at[0] !== null) {
        const t = svg("text", { class: "plabel", x: at[0].toFixed(3), y: (-at[1]).toFixed(3), "text-anchor": "middle", "dominant-baseline": "central" }, texts);
        V.setLabel(t, d.dot_text[j]);
      }
    });
    const angle = T("view.fp_at", { phi: V.fixed(sample.turn_deg, 1) });
    const lists = { forces: d.arrows.filter((a) => !a.resultant), found: d.arrows.filter((a) => a.resultant) };
    if (d.kind === "lever") {
      say(caption, "view.lever_caption", {
        at: angle, mu: V.written(d.plan_scale), scale: V.written(d.scale), mb: fmt(d.balancing, 5),
        fb: kN(Math.abs(d.balancing) / d.crank), forces: mark("forces"),
      }, lists);
    } else {
      say(caption, "view.fp_caption", {
        title: group.title, at: angle, scale: V.written(d.scale), closed: group.solved ? "" : T("view.fp_closed"),
        forces: mark("forces"), found: lists.found.length ? T("view.fp_found", { found: mark("found") }) : "",
      }, lists);
    }
  }

  // the kinds of arrow drawn, each a short stroke in its colour and its name
  function legend(p, d) {
    const box = $("force-plan-legend");
    box.replaceChildren();
    if (!d) return;
    const present = new Set(d.arrows.map((a) => a.kind));
    for (const kind in p.kinds) {
      if (!present.has(kind)) continue;
      const item = html("span", null, box, { class: "legend-item" });
      const s = svg("svg", { width: "26", height: "8", viewBox: "0 0 26 8" }, item);
      svg("line", { x1: 1, y1: 4, x2: 25, y2: 4, stroke: p.styles[kind].colour, "stroke-width": 2 }, s);
      item.appendChild(document.createTextNode(" " + p.kinds[kind]));
    }
  }

  V.on("show", () => update(V.state.index));
  V.on("index", (i) => update(i));
  $("force-plan-choice").addEventListener("change", () => update(V.state.index));
})();
