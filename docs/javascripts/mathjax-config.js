// MathJax reads this before it loads (docs/javascripts/mathjax/tex-svg.js, MathJax 3.2.2 shipped with the site):
// the formulas that pymdownx.arithmatex marks (\( \) inline, \[ \] displayed) are set as SVG, which needs no fonts
// to be fetched, so the pages show them opened from disk as well as from a server.
window.MathJax = {
  tex: { inlineMath: [["\\(", "\\)"]], displayMath: [["\\[", "\\]"]], processEscapes: true, processEnvironments: true },
  options: { ignoreHtmlClass: ".*|", processHtmlClass: "arithmatex", enableMenu: false },
  svg: { fontCache: "global" },
};
