// SPDX-License-Identifier: GPL-3.0-or-later
// Measures the plot's drawings as a browser lays them out (tests/tools/test_plot_layout.sh,
// scripts/check_plot.sh): appended to a page of section SVGs, it checks each element's box
// and writes one line per finding into <pre id="report">: "FAIL what" or "ok what".
// Checks: every text lies within its drawing; labels of a view (dimensions, station values,
// inset labels) within the view's frame; the text blocks (title, legend, parameter table,
// issues) overlap no view and no other text; each inset magnifies (at least x1.5); on the
// HTML page, the wheel zooms about the pointer, a drag pans, a double click restores.
(function () {
  var out = [];
  function fail(m) { out.push('FAIL ' + m); }
  function ok(m) { out.push('ok ' + m); }
  function overlap(a, b) { return a.x0 < b.x1 - 0.5 && b.x0 < a.x1 - 0.5 && a.y0 < b.y1 - 0.5 && b.y0 < a.y1 - 0.5; }
  function within(b, f) { return b.x0 >= f.x0 - 0.5 && b.x1 <= f.x1 + 0.5 && b.y0 >= f.y0 - 0.5 && b.y1 <= f.y1 + 0.5; }
  function words(t) { return '"' + t.textContent.slice(0, 50) + '"'; }
  var svgs = document.querySelectorAll('svg.section-plot');
  svgs.forEach(function (svg) {
    var id = svg.id, vb = svg.viewBox.baseVal, r = svg.getBoundingClientRect(), k = vb.width / r.width;
    function box(el) {
      var b = el.getBoundingClientRect();
      return {x0: (b.left - r.left) * k + vb.x, y0: (b.top - r.top) * k + vb.y,
              x1: (b.right - r.left) * k + vb.x, y1: (b.bottom - r.top) * k + vb.y};
    }
    var whole = {x0: 0, y0: 0, x1: vb.width, y1: vb.height}, bad = 0;
    svg.querySelectorAll('text').forEach(function (t) {
      if (!within(box(t), whole)) { ++bad; fail(id + ': text ' + words(t) + ' leaves the drawing'); }
    });
    var frames = [];
    svg.querySelectorAll('g.view').forEach(function (g) {
      var f = box(g.querySelector('rect.view-frame'));
      frames.push(f);
      g.querySelectorAll('.dim-label, .station-value, .inset-label').forEach(function (t) {
        if (t.classList.contains('inset-label') && g.classList.contains('inset')) return;  // above its frame
        if (!within(box(t), f)) { ++bad; fail(id + ': label ' + words(t) + ' is cut by its view'); }
      });
    });
    var blocks = Array.prototype.slice.call(
        svg.querySelectorAll('.title, .subtitle, .verdict, .legend text, .param-table text, .issues text'));
    blocks.forEach(function (t, i) {
      var b = box(t);
      frames.forEach(function (f) { if (overlap(b, f)) { ++bad; fail(id + ': text ' + words(t) + ' overlaps a view'); } });
      blocks.slice(i + 1).forEach(function (u) {
        if (overlap(b, box(u))) { ++bad; fail(id + ': texts ' + words(t) + ' and ' + words(u) + ' overlap'); }
      });
    });
    var main = svg.querySelector('g.view.main'), scale = main ? +main.getAttribute('data-scale') : 0;
    svg.querySelectorAll('g.view.inset').forEach(function (g) {
      var m = +g.getAttribute('data-scale') / scale;
      if (!(m >= 1.5)) { ++bad; fail(id + ': inset ' + g.id + ' magnifies x' + m.toFixed(2) + ' only'); }
    });
    if (!bad) ok(id + ': ' + svg.querySelectorAll('text').length + ' texts within their boxes');
  });
  // Pan and zoom, when the page carries its script.
  var self = document.currentScript, svg = svgs[0];
  var scripted = Array.prototype.some.call(document.scripts, function (s) {
    return s !== self && s.textContent.indexOf("'wheel'") >= 0;
  });
  if (svg && scripted) {
    var r = svg.getBoundingClientRect(), before = svg.viewBox.baseVal.width;
    var cx = r.left + 0.3 * r.width, cy = r.top + 0.4 * r.height;
    function user() {
      var v = svg.viewBox.baseVal, q = svg.getBoundingClientRect();
      return [v.x + (cx - q.left) / q.width * v.width, v.y + (cy - q.top) / q.height * v.height];
    }
    var p0 = user();
    svg.dispatchEvent(new WheelEvent('wheel', {deltaY: -400, clientX: cx, clientY: cy, bubbles: true, cancelable: true}));
    var p1 = user(), after = svg.viewBox.baseVal.width;
    if (after < 0.9 * before && Math.abs(p1[0] - p0[0]) < 0.5 && Math.abs(p1[1] - p0[1]) < 0.5)
      ok('the wheel zooms x' + (before / after).toFixed(2) + ' about the pointer');
    else fail('the wheel did not zoom about the pointer: width ' + before + ' -> ' + after + ', point ' + p0 + ' -> ' + p1);
    var x0 = svg.viewBox.baseVal.x;
    svg.dispatchEvent(new PointerEvent('pointerdown', {clientX: cx, clientY: cy, pointerId: 1, bubbles: true}));
    svg.dispatchEvent(new PointerEvent('pointermove', {clientX: cx + 50, clientY: cy, pointerId: 1, bubbles: true}));
    svg.dispatchEvent(new PointerEvent('pointerup', {clientX: cx + 50, clientY: cy, pointerId: 1, bubbles: true}));
    var moved = x0 - svg.viewBox.baseVal.x, expect = 50 / r.width * after;
    if (Math.abs(moved - expect) < 0.05) ok('a drag pans'); else fail('a drag moved ' + moved + ', not ' + expect);
    svg.dispatchEvent(new MouseEvent('dblclick', {bubbles: true}));
    if (Math.abs(svg.viewBox.baseVal.width - before) < 0.01 && Math.abs(svg.viewBox.baseVal.x) < 0.01)
      ok('a double click shows the drawing whole');
    else fail('a double click did not restore the view');
  } else if (svg && document.body.getAttribute('data-page') === 'html') {
    fail('the page has no pan and zoom');
  }
  var pre = document.createElement('pre');
  pre.id = 'report';
  pre.textContent = '\n' + out.join('\n') + '\n';
  document.body.appendChild(pre);
})();
