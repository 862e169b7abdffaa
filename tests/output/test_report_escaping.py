"""A scene's own text in the HTML report: a name, a note and a file name holding "</script>",
quotes, "&", "<!--" and tags are shown as written and change nothing in the page's structure:
its three scripts stay three and whole (the data parse as JSON), no tag comes from the text,
and every attribute still holds what it held."""

from html.parser import HTMLParser
import json

from click.testing import CliRunner

from flexlink.cli import main

from conftest import ROOT

NAME = "Evil </script><script>alert(\"x\")</script> 'quoted' & <b>bold</b> <!-- open"
NOTE = "assumed: </script> \"double\" & 'single' <!-- a comment --> <i>"
STEM = "evil\"scene'"  # quotes in the file name: the scene's id and folder carry them


class Page(HTMLParser):
    """Start tags with their attributes, each script's text, and each element's own text
    (tag, text) outside scripts."""

    VOID = {"meta", "br", "img", "input", "link", "hr", "col", "source"}

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.tags, self.scripts, self._texts, self._open = [], [], [], []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        if tag == "script":
            self.scripts.append("")
        if tag not in self.VOID:
            self._texts.append([tag, ""])
            self._open.append(len(self._texts) - 1)

    def handle_endtag(self, tag):
        while self._open:  # close up to the matching element (tolerates unclosed ones)
            if self._texts[self._open.pop()][0] == tag:
                break

    def handle_data(self, data):
        if not self._open:
            return
        entry = self._texts[self._open[-1]]
        if entry[0] == "script":
            self.scripts[-1] += data
        else:
            entry[1] += data

    @property
    def text(self) -> list[tuple[str, str]]:
        return [(tag, text) for tag, text in self._texts]


def test_a_scene_name_note_and_file_name_with_markup_leave_the_page_whole(tmp_path):
    scene = tmp_path / f"{STEM}.toml"
    title = NAME.replace("\\", "\\\\").replace('"', '\\"')
    note = NOTE.replace("\\", "\\\\").replace('"', '\\"')
    scene.write_text(f'base = "{ROOT / "cases" / "case1.toml"}"\nname = "{title}"\n'
                     f'[section]\nwidth = {{ value = "20 mm", note = "{note}" }}\n')
    out = tmp_path / "out"
    done = CliRunner().invoke(main, ["report", str(scene), "-e", "2", "-n", "1",
                                     "--cycle-poses", "0", "--out", str(out)])
    assert done.exit_code == 0, done.output
    page = Page()
    page.feed((out / "report.html").read_text())
    # the structure: the data, plotly and the player, nothing more; the data whole
    assert [tag for tag, _ in page.tags if tag == "script"] == ["script"] * 3
    assert len(page.scripts) == 3
    data = json.loads(page.scripts[0])
    assert set(data) == {"figures", "animations"} and list(data["animations"]) == [STEM]
    assert not any(tag in ("b", "i") for tag, _ in page.tags)  # no tag from the text
    # the text as written: the heading, the contents entry, the assumption's note
    assert ("h2", NAME) in page.text
    assert any(tag == "a" and text == NAME for tag, text in page.text)
    assert ("td", NOTE) in page.text
    # attributes keep the quotes of the file name, and links find their targets
    ids = [a["id"] for _, a in page.tags if "id" in a]
    assert f"scene-{STEM}" in ids
    hrefs = [a["href"] for tag, a in page.tags if tag == "a"]
    assert f"#scene-{STEM}" in hrefs
    files = [h for h in hrefs if not h.startswith("#")]
    assert files and all((out / h).is_file() for h in files), files
