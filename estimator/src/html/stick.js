// The frame's stick tool: two clicks on the frame (read in the frame's own pixels, whatever
// size the picture is shown at) and a typed length give the --stick flag to copy.
(function () {
  var svg = document.getElementById("frame-svg");
  if (!svg) return;
  var NS = "http://www.w3.org/2000/svg";
  var w = +svg.getAttribute("data-width"), h = +svg.getAttribute("data-height");
  var r = +svg.getAttribute("data-r");
  var marks = document.getElementById("stick-new");
  var metres = document.getElementById("stick-metres");
  var text = document.getElementById("stick-text");
  var copy = document.getElementById("stick-copy");
  var points = [];
  function half(v, most) { return Math.min(Math.max(Math.round(v * 2) / 2, 0), most); }
  function add(name, attrs) {
    var e = document.createElementNS(NS, name);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    marks.appendChild(e);
  }
  function show() {
    var m = parseFloat(metres.value);
    if (points.length < 2) {
      text.textContent = points.length ? "click the other end" : "click two ends of a known length";
    } else if (!(m > 0)) {
      text.textContent = "type the length between them, in metres";
    } else {
      text.textContent = "--stick " + points[0].join(",") + ":" + points[1].join(",") + "=" + m;
    }
    copy.disabled = text.textContent.indexOf("--stick") !== 0;
  }
  function draw() {
    while (marks.firstChild) marks.removeChild(marks.firstChild);
    if (points.length === 2) {
      add("line", { x1: points[0][0], y1: points[0][1], x2: points[1][0], y2: points[1][1] });
    }
    points.forEach(function (p) { add("circle", { cx: p[0], cy: p[1], r: r }); });
    show();
  }
  svg.addEventListener("click", function (e) {
    var b = svg.getBoundingClientRect();
    if (points.length === 2) points = [];
    points.push([half((e.clientX - b.left) * w / b.width, w), half((e.clientY - b.top) * h / b.height, h)]);
    draw();
  });
  metres.addEventListener("input", show);
  copy.addEventListener("click", function () {
    if (navigator.clipboard) navigator.clipboard.writeText(text.textContent);
  });
  show();
})();
