// linkwork viewer: the forces on the scheme at the crank angle shown (linkwork.web.arrows).
//
// Each joint's reaction on its link of the highest number (R12: of link 1 on link 2, at the joint), the
// forces of the file's loads on their points (the knives' cutting force), all to one scale: an arrow of
// force F is F / mu_F mm long in the drawing of the mechanism at full size (data-scale on #forces: m per
// N); and the driving torque, an arc about the crank's pivot turning the way it turns the crank.  Shown
// while the "forces" box is ticked.  The scale is that of the mechanism as loaded (so that an edit's
// arrows compare with the file's), divided by the zoom chosen beside the box.  An arrow longer than a fifth of
// the scheme (the knives' forces during the cut) is drawn that long and dashed, so that it stays in the panel;
// the labels of the forces are set clear of each other and of the joints' names.
"use strict";

(function () {
  const V = window.linkworkViewer;
  const { $, svg, fmt, T } = V;
  const KINDS = ["reaction", "load", "torque"];

  function layer(m) {
    let g = $("forces");
    if (!g) g = svg("g", { id: "forces" }, $("scheme"));
    const handles = $("handles");
    if (handles) $("scheme").insertBefore(g, handles); // under the handles
    g.replaceChildren();
    g.setAttribute("display", $("show-forces").checked ? "inline" : "none");
    const defs = svg("defs", {}, g);
    const head = (1000 * 1.6 * m.scene.r).toFixed(3);
    for (const kind of KINDS) {
      const mk = svg("marker", {
        id: `force-head-${kind}`, viewBox: "0 0 10 10", refX: "10", refY: "5", orient: "auto-start-reverse",
        markerWidth: head, markerHeight: head, markerUnits: "userSpaceOnUse",
      }, defs);
      svg("path", { d: "M0,1 L10,5 L0,9 z", class: "force-head " + kind }, mk);
    }
    return g;
  }

  function kN(v) { return Math.abs(v) >= 1000 ? `${fmt(v / 1000, 3)} ${T("unit.kN")}` : `${fmt(v, 3)} ${T("unit.N")}`; }

  // the arrows of a model; returns the function that places them at a sample
  function build(m) {
    const g = layer(m);
    const box = $("show-forces"), caption = $("forces-caption");
    const f = m.forces;
    box.disabled = !f.available;
    box.parentElement.title = f.available ? "" : T("view.forces_off", { reason: f.reason });
    if (!f.available || !f.arrows) { caption.hidden = true; return null; }
    const loaded = V.state.base.forces.scale_per_mm || f.scale_per_mm;
    const scale = loaded / Number($("force-zoom").value); // N per mm of the drawing at full size
    g.setAttribute("data-scale", String(1 / (1000 * scale)));
    g.setAttribute("data-transform", "arrow (x2 - x1, y1 - y2) mm = 1000 F data-scale, F in N");
    const size = 1000 * m.scene.size, em = 1000 * m.scene.em;
    const arrows = f.arrows.map((a, k) => {
      const line = svg("line", {
        class: "force " + a.kind, "data-kind": a.kind, "data-name": a.name, "data-on": a.on, "data-arrow": String(k),
        "marker-end": `url(#force-head-${a.kind})`,
      }, g);
      const text = svg("text", { class: "force-label " + a.kind, "font-size": (0.8 * em).toFixed(3), "text-anchor": "middle", "dominant-baseline": "central" }, g);
      V.setLabel(text, a.label); // R12 with its subscript, as the scheme names its joints (O1)
      return { a, k, line, text };
    });
    const torque = svg("path", { class: "force torque", "marker-end": "url(#force-head-torque)" }, g);
    const torqueText = svg("text", { class: "force-label torque", "font-size": (0.8 * em).toFixed(3) }, g);
    const torqueSeries = m.series.find((s) => s.key === "torque");
    const hide = (...els) => els.forEach((e) => e.setAttribute("visibility", "hidden"));

    // an arrow longer than MOST of the scheme's size (the knives' force during the cut) is drawn that long,
    // dashed ("beyond": not to scale), so that it stays in the panel; its label still says its force
    const MOST = 0.2;
    function arrow({ a, k, line, text }, i, placed) {
      const at = m.positions.at(i, a.point), F = m.valid[i] ? f.values.at(i, k) : null;
      if (!at || !F || !isFinite(F[1])) { hide(line, text); return null; }
      const x1 = 1000 * at[0], y1 = -1000 * at[1];
      let x2 = x1 + F[0] / scale, y2 = y1 - F[1] / scale;
      let len = Math.hypot(x2 - x1, y2 - y1);
      if (len < 1e-6 * size) { hide(line, text); return `${a.label} 0`; }
      const beyond = len > MOST * size;
      if (beyond) {
        x2 = x1 + ((x2 - x1) * MOST * size) / len; y2 = y1 + ((y2 - y1) * MOST * size) / len; len = MOST * size;
      }
      line.classList.toggle("beyond", beyond);
      line.setAttribute("data-beyond", String(beyond));
      line.setAttribute("visibility", "visible"); text.setAttribute("visibility", "visible");
      line.setAttribute("x1", x1.toFixed(4)); line.setAttribute("y1", y1.toFixed(4));
      line.setAttribute("x2", x2.toFixed(4)); line.setAttribute("y2", y2.toFixed(4));
      const [x, y] = clear(x2, y2, (x2 - x1) / len, (y2 - y1) / len, a.label, placed);
      text.setAttribute("x", x.toFixed(3)); text.setAttribute("y", y.toFixed(3));
      return `${a.label} ${kN(Math.hypot(F[0], F[1]))}${beyond ? T("view.shortened") : ""}`;
    }

    // where a force's label goes: beyond its arrow's head, pushed on along the arrow, then to either side of
    // it, until its box covers no label placed before (the other forces', the joints')
    function clear(x, y, ux, uy, label, placed) {
      const w = 0.62 * 0.8 * em * label.length, h = 0.8 * 1.2 * em;
      const hits = (cx, cy) => placed.some((b) => Math.abs(cx - b[0]) < (w + b[2]) / 2 && Math.abs(cy - b[1]) < (h + b[3]) / 2);
      const tries = [];
      for (const along of [0.9, 1.8, 2.7, 3.6]) for (const side of [0, 1.2, -1.2, 2.4, -2.4]) tries.push([along, side]);
      for (const [along, side] of tries) {
        const cx = x + along * em * ux - side * em * uy, cy = y + along * em * uy + side * em * ux;
        if (!hits(cx, cy)) { placed.push([cx, cy, w, h]); return [cx, cy]; }
      }
      const cx = x + 0.9 * em * ux, cy = y + 0.9 * em * uy;
      placed.push([cx, cy, w, h]);
      return [cx, cy];
    }

    // the boxes of the scheme's labels at sample i (the joints' names, the links' numbers), in the drawing's mm
    function schemeLabels(i) {
      return V.state.data.scene.labels.map((lab) => {
        const c = lab.centre.at(i, 0);
        return c ? [1000 * c[0], -1000 * c[1], 0.62 * em * lab.text.length, 1.2 * em] : null;
      }).filter(Boolean);
    }

    // an arc of 270 degrees about the crank's pivot, its head counter-clockwise for a positive torque
    function turning(i) {
      const M = torqueSeries ? torqueSeries.values[i] : null;
      const centre = m.positions.at(i, f.torque_point);
      if (M === null || !centre || !m.valid[i]) { hide(torque, torqueText); return null; }
      torque.setAttribute("visibility", "visible"); torqueText.setAttribute("visibility", "visible");
      const r = 3.5 * 1000 * m.scene.r, cx = 1000 * centre[0], cy = -1000 * centre[1];
      const a0 = -Math.PI / 4, a1 = a0 + 1.5 * Math.PI;
      const pt = (a) => `${(cx + r * Math.cos(a)).toFixed(3)},${(cy - r * Math.sin(a)).toFixed(3)}`;
      const [s, e] = M >= 0 ? [a0, a1] : [a1, a0];
      torque.setAttribute("d", `M${pt(s)} A${r.toFixed(3)},${r.toFixed(3)} 0 1 ${M >= 0 ? 0 : 1} ${pt(e)}`);
      torque.setAttribute("data-torque", String(M));
      torqueText.setAttribute("x", (cx + 1.1 * r).toFixed(3));
      torqueText.setAttribute("y", (cy - 1.1 * r).toFixed(3));
      torqueText.textContent = T("view.torque", { value: fmt(M, 4) }); // as the caption and the torque chart say it
      return M;
    }

    return (i) => {
      const placed = schemeLabels(i);
      const shown = arrows.map((x) => arrow(x, i, placed)).filter((s) => s !== null);
      const M = turning(i);
      caption.hidden = !box.checked;
      caption.textContent = T("view.forces_caption", { scale: fmt(scale, 3), forces: V.listed(shown) }) +
        (M === null ? "" : T("view.forces_torque", { value: fmt(M, 4) }));
    };
  }

  // drawn only while shown: an edit's answer is not drawn twice
  let update = null, model = null;
  function refresh() {
    update = model && $("show-forces").checked ? build(model) : null;
    if (!update) {
      const f = model && model.forces;
      $("show-forces").disabled = !(f && f.available);
      $("forces-caption").hidden = true;
      const g = $("forces");
      if (g) g.setAttribute("display", $("show-forces").checked ? "inline" : "none");
    }
  }
  V.on("show", (m) => { model = m; refresh(); });
  V.on("index", (i) => { if (update) update(i); });
  $("show-forces").addEventListener("change", () => {
    refresh();
    if (update) update(V.state.index);
  });
  $("force-zoom").addEventListener("change", () => {
    refresh();
    if (update) update(V.state.index);
  });
})();
