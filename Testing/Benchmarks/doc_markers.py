"""Documentation pages whose tables a benchmark regenerates: the tables sit
between <!-- NAME --> and <!-- /NAME --> markers, the prose around them is
written by hand. No VTK import, so that every benchmark script can use it."""


def replace_between_markers(page, marker, lines):
    """Replace what lies between <!-- MARKER --> and <!-- /MARKER --> in the
    Markdown file `page` by `lines` (a list of strings), keeping the rest of
    the page. Exits naming the page and the markers when they are missing."""
    with open(page) as f:
        text = f.read()
    begin, end = "<!-- %s -->" % marker, "<!-- /%s -->" % marker
    if begin not in text or end not in text:
        raise SystemExit("%s has no %s ... %s markers" % (page, begin, end))
    head, rest = text.split(begin, 1)
    tail = rest.split(end, 1)[1]
    with open(page, "w") as f:
        f.write(head + begin + "\n" + "\n".join(lines) + "\n" + end + tail)
