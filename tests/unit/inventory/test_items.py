"""The inventory reader (opsrock.inventory.items) and the friction laws (opsrock.inventory.friction): both file
formats read the same items, every column round-trips through the writer, the friction draws are deterministic
per (seed, case id) and have the distributions' moments, the shipped inventories load, and every bad value is
refused with one line naming the file, the line, the column and the value."""

from __future__ import annotations

import dataclasses
import hashlib
import math
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate, stats

from opsrock.campaign.grid import Grid
from opsrock.campaign.scene import BlockSpec, Scene, load_blocks
from opsrock.data import block_library
from opsrock.errors import ImplausibleInputError, InputError
from opsrock.inventory.friction import MU_MAX, FrictionDistribution, FrictionLaw, parse_friction, unit_draw
from opsrock.inventory.items import (COLUMNS, Inventory, Item, Support, item_cells, read_inventory, shipped_inventory,
                                     write_inventory)
from opsrock.inventory.campaigns import item_block_spec
from opsrock.inventory.readers import TableFileError

HEADER = ",".join(COLUMNS)

#: One inventory with every column given, as CSV (BOM, comments, blank lines, spaces, any-case header).
FULL_CSV = ("\ufeff# an inventory with every column\n\n"
            + " ID , Description ,width,depth,height,mass,cm_height,radius_of_gyration,friction,friction_kinetic,"
              "restitution,fema_id,floor,quantity,support_period,support_damping,repair_cost,slide_distance,slide_cost\n"
            + "cab, low cabinet ,1.2,0.45,0.75,80,,,\"lognormal(median=0.4, beta=0.25)\",0.3,,,1;2; 3 ,4,,,500,0.1,60\n"
            + "# a comment between rows\n"
            + "book,loaded bookcase,0.320675,0.9144,1.8034,135,0.78,0.5,,,0.8,E.20.22.105a,,12,,,300\n"
            + "printer,\"printer, on a desk\",0.42,0.46,0.5,25,,,0.5,0.4,,,2;3,3,0.2,0.07,800.5\n")

FULL_TOML = """# the same inventory as TOML
[[item]]
id = "cab"
description = "low cabinet"
width = 1.2
depth = 0.45
height = 0.75
mass = 80
friction = "lognormal(median=0.4, beta=0.25)"
friction_kinetic = 0.3
floor = ["1", "2", 3]
quantity = 4
repair_cost = 500
slide_distance = 0.1
slide_cost = 60

[[item]]
id = "book"
description = "loaded bookcase"
width = 0.320675
depth = 0.9144
height = 1.8034
mass = 135
cm_height = 0.78
radius_of_gyration = 0.5
restitution = 0.8
fema_id = "E.20.22.105a"
quantity = 12
repair_cost = 300

[[item]]
id = "printer"
description = "printer, on a desk"
width = 0.42
depth = 0.46
height = 0.5
mass = 25
friction = 0.5
friction_kinetic = 0.4
floor = "2;3"
quantity = 3
support_period = 0.2
support_damping = 0.07
repair_cost = 800.5
"""


def _write(tmp_path: Path, text: str, name: str = "inv.csv") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _narrow(tmp_path: Path, text: str, name: str) -> Path:
    """``text`` with the low cabinet made narrow enough (width/height < sqrt 2) for a Block without the wide-block
    change, so that the format tests run on every branch."""
    return _write(tmp_path, text.replace("1.2", "1.0"), name)


# --- both formats, every column --------------------------------------------------------------------------
def test_csv_and_toml_read_the_same_inventory(tmp_path):
    a = read_inventory(_narrow(tmp_path, FULL_CSV, "inv.csv"))
    b = read_inventory(_narrow(tmp_path, FULL_TOML, "inv.toml"))
    assert a.items == b.items
    cab, book, printer = a.items
    assert cab.friction == FrictionLaw("lognormal", (0.4, 0.25), kinetic_ratio=0.3 / cab.friction.median)
    assert cab.floors == ("1", "2", "3") and cab.quantity == 4.0 and cab.repair_cost == 500.0
    assert (book.cm_height, book.radius_of_gyration, book.restitution, book.fema_id) == (0.78, 0.5, 0.8, "E.20.22.105a")
    assert book.floors == () and book.friction is None and book.support is None
    assert printer.description == "printer, on a desk" and printer.support == Support(0.2, 0.07)
    assert printer.friction == FrictionLaw("fixed", (0.5,)) and printer.friction_kinetic == 0.4
    assert printer.repair_cost == 800.5


@pytest.mark.parametrize("suffix", [".csv", ".toml"])
def test_every_column_round_trips_through_the_writer(tmp_path, suffix):
    original = read_inventory(_narrow(tmp_path, FULL_CSV, "inv.csv"))
    given = {c for it in original.items for c in _given(it)}
    # the inventory exercises every column but a round base's (test_a_round_item_has_a_diameter_in_place_of_width...)
    assert given == set(COLUMNS) - {"shape", "diameter"}
    back = read_inventory(write_inventory(original, tmp_path / f"out{suffix}"))
    assert back.items == original.items


def _given(item: Item) -> set[str]:
    return set(item_cells(item))


def test_a_blank_optional_cell_takes_its_default(tmp_path):
    inv = read_inventory(_write(tmp_path, "id,description,width,depth,height,mass,quantity,floor\n"
                                          "a,box,0.4,0.5,1.0,,,\n"))
    assert inv.items[0] == Item("a", "box", 0.4, 0.5, 1.0)


def test_fewer_cells_than_the_header_are_blank(tmp_path):
    inv = read_inventory(_write(tmp_path, "id,description,width,depth,height,mass\na,box,0.4,0.5,1.0\n"))
    assert inv.items[0].mass is None


# --- the friction draws ---------------------------------------------------------------------------------
LAWS = [FrictionLaw("uniform", (0.3, 0.5)), FrictionLaw("normal", (0.4, 0.05)),
        FrictionLaw("lognormal", (0.4, 0.25))]


@pytest.mark.parametrize("law", LAWS, ids=lambda law: law.distribution)
def test_a_draw_is_deterministic_per_seed_and_case_id(law):
    a = law.draw("bookcase/rec1/f2/l03", 7)
    assert a == law.draw("bookcase/rec1/f2/l03", 7)  # the same seed and id: the same draw, in any process
    assert a != law.draw("bookcase/rec1/f2/l04", 7)  # another case
    assert a != law.draw("bookcase/rec1/f2/l03", 8)  # another seed
    assert 0.0 < a <= MU_MAX


def test_the_friction_stream_is_not_the_restitution_stream():
    # opsrock.restitution draws u from default_rng([seed, key]); friction adds its own stream, so that the two
    # draws of one case are independent (the same u in both would correlate friction with restitution)
    key = int.from_bytes(hashlib.sha256(b"c1").digest()[:8], "little")
    assert unit_draw(3, "c1") != float(np.random.default_rng([3, key]).random())


#: Reference distributions (scipy, an implementation independent of the stdlib NormalDist the law uses).
def _reference(law: FrictionLaw):
    a, b = law.parameters
    if law.distribution == "uniform":
        return stats.uniform(loc=a, scale=b - a)
    if law.distribution == "normal":
        return stats.truncnorm(-a / b, (MU_MAX - a) / b, loc=a, scale=b)
    return None  # lognormal truncated at MU_MAX: moments by quadrature below


def _moments(law: FrictionLaw) -> tuple[float, float]:
    ref = _reference(law)
    if ref is not None:
        return float(ref.mean()), float(ref.std())
    m, beta = law.parameters
    dist = stats.lognorm(s=beta, scale=m)
    mass = dist.cdf(MU_MAX)
    m1 = integrate.quad(lambda x: x * dist.pdf(x), 0, MU_MAX)[0] / mass
    m2 = integrate.quad(lambda x: x * x * dist.pdf(x), 0, MU_MAX)[0] / mass
    return m1, math.sqrt(m2 - m1 * m1)


@pytest.mark.parametrize("law", LAWS, ids=lambda law: law.distribution)
def test_draws_have_the_distribution_s_moments(law):
    draws = np.array([law.draw(f"item/rec{k}/f1/l00", 2026) for k in range(2000)])
    mean, std = _moments(law)
    # the sample mean of 2,000 draws has a standard error std/sqrt(2000) (2.2 % of std); 4 standard errors is a
    # bound a correct sampler exceeds with probability 6e-5 (and the draws are fixed by the seed, so the test
    # either always passes or always fails). The sample std's standard error is about std/sqrt(2*2000) for
    # these near-normal laws (the uniform's is smaller); 4 of them is 9 % of std.
    assert abs(draws.mean() - mean) < 4 * std / math.sqrt(2000)
    assert abs(draws.std(ddof=1) - std) < 4 * std / math.sqrt(2 * 2000)


@pytest.mark.parametrize("law", LAWS[:2], ids=lambda law: law.distribution)
@pytest.mark.parametrize("u", [1e-6, 0.01, 0.3, 0.5, 0.9, 0.999999])
def test_the_quantile_is_scipy_s(law, u):
    # the inverse transform against scipy's ppf of the same truncated distribution (independent code)
    assert law.quantile(u) == pytest.approx(float(_reference(law).ppf(u)), rel=1e-9)


@pytest.mark.parametrize("u", [1e-6, 0.01, 0.5, 0.9, 0.999999])
def test_the_lognormal_quantile_is_scipy_s(u):
    law = FrictionLaw("lognormal", (0.4, 0.25))
    dist = stats.lognorm(s=0.25, scale=0.4)
    assert law.quantile(u) == pytest.approx(float(dist.ppf(u * dist.cdf(MU_MAX))), rel=1e-9)


def test_a_kinetic_coefficient_with_a_distribution_scales_with_each_draw(tmp_path):
    item = Item("cab", "cabinet", 0.4, 0.5, 0.75, friction=parse_friction("uniform(0.3, 0.5)"), friction_kinetic=0.32)
    spec = item_block_spec(item, "1", "cab.d1", seed=5)
    block = spec.block_for("cab.d1/r/f/l1")
    mu = item.friction.draw("cab.d1/r/f/l1", 5)
    assert block.friction == mu and block.friction_kinetic == pytest.approx(mu * 0.32 / 0.4, rel=1e-12)


@pytest.mark.parametrize("text, law", [
    ("0.4", FrictionLaw("fixed", (0.4,))), (" 0 ", FrictionLaw("fixed", (0.0,))),
    ("uniform(0.3, 0.5)", FrictionLaw("uniform", (0.3, 0.5))),
    ("Uniform( high = 0.5 , low=0.3 )", FrictionLaw("uniform", (0.3, 0.5))),
    ("normal(0.4, 0.05)", FrictionLaw("normal", (0.4, 0.05))),
    ("lognormal(median=0.4, beta=0.2)", FrictionLaw("lognormal", (0.4, 0.2)))])
def test_friction_texts_parse(text, law):
    assert parse_friction(text) == law
    assert parse_friction(law.text) == law  # the writer's text reads back


# --- the planar blocks ----------------------------------------------------------------------------------
def test_block_spec_puts_width_along_direction_1_and_depth_along_2():
    item = Item("rack", "rack", 0.6, 1.07, 2.0, mass=450, friction=FrictionLaw("fixed", (0.5,)), friction_kinetic=0.45,
                restitution=0.7)
    one, two = item_block_spec(item, "1", "rack.d1"), item_block_spec(item, "2", "rack.d2")
    assert (one.width, two.width, one.height, two.height) == (0.6, 1.07, 2.0, 2.0)
    assert (one.friction, one.friction_kinetic, one.restitution, one.mass) == (0.5, 0.45, 0.7, 450.0)
    assert one.friction_distribution is None and one.block_for("x") == one.block
    with pytest.raises(InputError, match="direction = '3'"):
        item_block_spec(item, "3", "rack.d3")


def test_block_spec_draws_a_friction_distribution_per_case():
    item = Item("cab", "cabinet", 0.4, 0.5, 0.75, friction=parse_friction("normal(0.4, 0.05)"))
    spec = item_block_spec(item, "2", "cab.d2", seed=11)
    assert spec.friction_distribution == FrictionDistribution(item.friction, 11)
    assert spec.friction == pytest.approx(0.4, abs=1e-12)  # the median of a normal barely truncated
    draws = {spec.block_for(f"cab.d2/r{k}/f1/l00").friction for k in range(5)}
    assert len(draws) == 5 and draws == {item.friction.draw(f"cab.d2/r{k}/f1/l00", 11) for k in range(5)}


def test_a_scene_s_digest_sees_the_friction_distribution():
    grid = Grid(freq_ratio=(2.0,), pfa_ratio=(1.5,))
    specs = [item_block_spec(Item("cab", "c", 0.4, 0.5, 0.75, friction=parse_friction(text)), "1", "cab")
             for text in ("normal(0.4, 0.05)", "normal(0.4, 0.1)")]
    digests = {Scene("s", "", (spec,), grid, solver="friction").digest() for spec in specs}
    assert len(digests) == 2  # the same median, another spread: another campaign


def test_block_spec_carries_the_mass_distribution():
    item = Item("book", "bookcase", 0.32, 0.91, 1.8, cm_height=0.78, radius_of_gyration=0.5)
    spec = item_block_spec(item, "1", "book.d1")
    assert spec.block == dataclasses.replace(item.planar_block("1"), name="book.d1")
    assert spec.block.h_cm == 0.78 and spec.block.r_gyration == 0.5


def test_floors_in_the_motions():
    item = Item("a", "a", 0.4, 0.5, 1.0, floors=("3", "1"))
    assert item.floors_in(("1", "2", "3")) == ("1", "3")
    assert Item("b", "b", 0.4, 0.5, 1.0).floors_in(("1", "2")) == ("1", "2")
    with pytest.raises(InputError, match="item 'a': floor '3' is not among"):
        item.floors_in(("1", "2"))


# --- the shipped inventories ----------------------------------------------------------------------------
def test_fema_p58_nine_is_the_blocks_library():
    inv = shipped_inventory("fema-p58-nine")
    library = load_blocks(block_library("fema-p58-contents"))
    assert inv.source == "shipped:fema-p58-nine" and len(inv.items) == 9
    for item, spec in zip(inv.items, library):
        assert (item.id, item.fema_id, item.width, item.height) == (spec.name, spec.name, spec.width, spec.height)
        assert item.friction is None and item.floors == () and item.quantity == 1.0
        assert item_block_spec(item, "1", spec.name).block == spec.block  # the same rocking block in direction 1


def test_the_example_inventory_loads():
    inv = shipped_inventory("example")
    assert inv.ids == ("low_cabinet", "bookcase", "server_rack", "printer", "oxygen_cylinder")
    cab, book, rack, printer, o2 = inv.items
    assert cab.width / cab.height > math.sqrt(2) and not cab.friction.fixed  # a wide block, friction drawn
    assert book.cm_height < book.height / 2 and book.radius_of_gyration is not None and book.fema_id
    assert rack.repair_cost and printer.support is not None and 0.1 <= printer.support.period <= 0.3
    assert {f for it in inv.items for f in it.floors} == {"1", "2", "3"}
    assert o2.shape == "cylinder" and o2.width == o2.depth == 0.23 and o2.height == 1.5  # a round item (issue 45)


def test_an_unknown_shipped_inventory_is_refused():
    with pytest.raises(InputError, match="no shipped inventory 'nine'.*example, fema-p58-nine"):
        shipped_inventory("nine")


# --- refusals: one line naming the file, the line, the column and the value -----------------------------
def _row(cells: str) -> str:
    """A CSV inventory of one item, the first columns given and ``cells`` for the rest (``mass,...``)."""
    names, values = cells.split("|") if "|" in cells else ("", "")
    head = "id,description,width,depth,height" + (f",{names}" if names else "")
    return f"{head}\nbox,a box,0.4,0.5,1.0{',' + values if names else ''}\n"


BAD_CELLS = [
    ("mass|abc", "mass = 'abc': is not a number"), ("mass|nan", "mass = 'nan': is not a number"),
    ("mass|1_000", "mass = '1_000': is not a number"), ("mass|-5", "mass = '-5'"),
    ("cm_height|1.5", "cm_height = '1.5': cm_height must lie in (0, height]"),
    ("radius_of_gyration|2", "radius_of_gyration = '2'"),
    ("restitution|1.5", "restitution = '1.5': restitution must lie in (0, 1]"),
    ("friction,friction_kinetic|0.3,0.4", "friction_kinetic = '0.4'"),
    ("friction_kinetic|0.4", "friction_kinetic = '0.4': friction_kinetic = 0.4 needs friction"),
    ("friction|-0.1", "friction = '-0.1'"), ("friction|high", "friction = 'high': friction: 'high' is neither"),
    ("friction|\"weibull(1, 2)\"", "unknown distribution 'weibull'"),
    ("friction|weibull(1, 2)", "7 cells where the header names 6 columns (first extra value '2)'; quote a cell"),
    ("friction|uniform(0.5)", "uniform takes 2 parameters"),
    ("friction|\"uniform(0.5, 0.3)\"", "needs 0 <= low < high <= 1.3"),
    ("friction|\"uniform(0.3, 2)\"", "needs 0 <= low < high <= 1.3"),
    ("friction|\"normal(0.1, 0.2)\"", "puts 30.9% of its draws outside (0, 1.3]"),
    ("friction|\"normal(0.4, -0.1)\"", "friction normal std must be a positive"),
    ("friction|\"lognormal(median=0, beta=0.2)\"", "friction lognormal median must be a positive"),
    ("friction|\"lognormal(median=0.4, sigma=0.2)\"", "takes the parameters lognormal(median, beta)"),
    ("friction|\"lognormal(median=0.4, 0.2)\"", "all by position or all by name"),
    ("friction|\"normal(0.4, x)\"", "normal std = 'x' is not a number"),
    ("friction,friction_kinetic|\"uniform(0.3, 0.5)\",0.5", "friction_kinetic = 0.5 exceeds the median static friction 0.4 of uniform(low=0.3, high=0.5)"),
    ("fema_id|E.20.22.107a", "fema_id = 'E.20.22.107a': no FEMA P-58 unanchored item"),
    ("floor|a b", "floor = 'a b': floor 'a b' must use only"), ("floor|1;1", "floor = '1;1': floor lists '1' twice"),
    ("floor|1;;2", "floor = '1;;2': floor '' must use only"),
    ("quantity|0", "quantity = '0': quantity must be an integer in [1, 1000000]"),
    ("quantity|1.5", "quantity = '1.5': is not a whole number of units"),
    ("support_damping|0.05", "support_damping = '0.05': support_damping needs support_period"),
    ("support_period|0", "support_period = '0': support_period must lie in [0.01, 10] s"),
    ("support_period,support_damping|0.2,0.9", "support_damping = '0.9': support_damping must lie in [0, 0.5]"),
    ("repair_cost|-1", "repair_cost = '-1': repair_cost must be a finite number >= 0"),
    # a priced slide without a priced overturning: pelicun's loss would count an overturned unit at nothing
    ("slide_cost|60", "slide_cost = '60': item 'box' prices a displaced unit (slide_cost) but not an overturned one"),
]


@pytest.mark.parametrize("cells, needle", BAD_CELLS, ids=[c for c, _ in BAD_CELLS])
def test_a_bad_cell_is_refused_naming_file_line_column_value(tmp_path, cells, needle):
    path = _write(tmp_path, _row(cells))
    with pytest.raises(TableFileError) as err:
        read_inventory(path)
    message = str(err.value)
    assert message.startswith(f"{path}:2: ") and needle in message and "\n" not in message
    assert err.value.argument == err.value.column


@pytest.mark.parametrize("text, line, needle", [
    ("", None, "empty file: no header row"), ("# only a comment\n\n", None, "empty file"),
    ("id,description,width,depth,height\n", 1, "no rows after the header"),
    ("id,description,width,depth,height,colour\n", 1, "header = 'colour': unknown column (known: id, description"),
    ("id,description,width,depth,height,mass,MASS\n", 1, "header = 'mass': column named twice"),
    # a box's row without its depth (a cylinder's has a diameter in its place, issue 45)
    ("id,description,width,height\nbox,b,0.4,1\n", 2, "depth: blank: a box needs its width and depth"),
    ("id,description,width,depth,height\nbox,,0.4,0.5,1\n", 2, "description: blank: every item needs it"),
    ("id,description,width,depth,height\nbox,b,0.4,0.5,1,7\n", 2, "6 cells where the header names 5 columns"),
    ("id,description,width,depth,height\nbox/1,b,0.4,0.5,1\n", 2, "id = 'box/1': id = 'box/1' must use only"),
    ("id,description,width,depth,height\nbox,b,0,0.5,1\n", 2, "width = '0': width must lie in [0.001, 1000] m"),
    ("id,description,width,depth,height\nbox,b,0.4,-1,1\n", 2, "depth = '-1': depth must lie in"),
    ("id,description,width,depth,height\nbox,b,0.4,0.5,inf\n", 2, "height = 'inf': is not a number"),
    ("id,description,width,depth,height\n# c\nbox,b,0.4,0.5,1\n\nbox,c,0.3,0.5,1\n", 5,
     "id = 'box': used twice (first on line 3)"),
    ("id,description,width,depth,height\nbox,\"b,0.4,0.5,1\n", 2, "not valid CSV"),
])
def test_a_bad_table_is_refused(tmp_path, text, line, needle):
    path = _write(tmp_path, text)
    with pytest.raises(TableFileError) as err:
        read_inventory(path)
    where = f"{path}:{line}: " if line else f"{path}: "
    assert str(err.value).startswith(where) and needle in str(err.value), str(err.value)


def test_a_radius_of_gyration_too_large_in_direction_2_only_names_it(tmp_path):
    # the largest radius of gyration is the distance from the centre of mass to the farthest corner, which
    # depends on the base along the motion: 0.6 m fits a 1.2-m deep block (direction 2) but not 0.2 m (1)
    path = _write(tmp_path, "id,description,width,depth,height,radius_of_gyration\nb,b,1.2,0.2,1.0,0.6\n")
    with pytest.raises(TableFileError, match=r"radius_of_gyration = '0.6': .*\(direction 2: depth 0.2 m along"):
        read_inventory(path)


def test_a_block_size_in_millimetres_is_refused_with_its_likely_unit(tmp_path):
    path = _write(tmp_path, "id,description,width,depth,height\nbox,b,400,500,900\n")
    with pytest.raises(ImplausibleInputError, match=rf"{path} line 2: width = 400 m exceeds 10 m.*looks like millimetres"
                                                   r".*--accept-implausible"):
        read_inventory(path)
    assert read_inventory(path, confirm=True).items[0].width == 400.0


@pytest.mark.parametrize("text, needle", [
    ("[[item]]\nid = 'a'\ndescription = 'b'\nwidth = 0.4\ndepth = 0.5\nheight = 1\ncolour = 'red'\n",
     ":7: colour = 'red': unknown key (known: id,"),
    ("[[item]]\nid = 'a'\ndescription = 'b'\nwidth = 0.4\nheight = 1\n", ":1: depth: blank: a box needs its width and"),
    ("[[item]]\nid = 'a'\ndescription = 'b'\nwidth = '0.4'\ndepth = 0.5\nheight = 1\n",
     ":4: width = '0.4': must be a number, not str"),
    ("[[item]]\nid = 'a'\ndescription = 'b'\nwidth = 0.4\ndepth = 0.5\nheight = 1\nmass = true\n",
     ":7: mass = True: must be a number, not bool"),
    ("[[item]]\nid = 'a'\ndescription = 'b'\nwidth = 0.4\ndepth = 0.5\nheight = 1\nmass = nan\n",
     ":7: mass = nan: is not a finite number"),
    ("title = 'x'\n[[item]]\nid = 'a'\n", ": title: unknown key: the file holds [[item]] tables only"),
    ("[item]\nid = 'a'\n", ": item: needs at least one [[item]] table"), ("", ": item: needs at least one"),
    ("[[item]\nid = 1\n", ": not valid TOML"),
])
def test_a_bad_toml_inventory_is_refused(tmp_path, text, needle):
    path = _write(tmp_path, text, "inv.toml")
    with pytest.raises(TableFileError) as err:
        read_inventory(path)
    assert str(err.value).startswith(str(path)) and needle in str(err.value), str(err.value)


@pytest.mark.parametrize("make, needle", [
    (lambda p: p, "no such file"), (lambda p: (p.mkdir(), p)[1], "is a folder, not a file"),
    (lambda p: (p.write_bytes(b"id,description\n\xff\xfe\n"), p)[1], "not UTF-8 text"),
])
def test_an_unreadable_file_is_refused(tmp_path, make, needle):
    path = make(tmp_path / "inv.csv")
    with pytest.raises(TableFileError, match=rf"^{path}: .*{needle}"):
        read_inventory(path)


def test_an_item_made_in_code_is_checked_too():
    with pytest.raises(InputError, match="quantity must be positive") as err:
        Item("a", "a", 0.4, 0.5, 1.0, quantity=-1)
    assert err.value.argument == "quantity"
    with pytest.raises(InputError, match="id 'a' is used twice"):
        Inventory((Item("a", "a", 0.4, 0.5, 1.0),) * 2, "code")
    with pytest.raises(InputError, match="no items"):
        Inventory((), "code")


def test_a_round_item_has_a_diameter_in_place_of_width_and_depth(tmp_path):
    """Issue 45: ``shape = cylinder`` with a ``diameter``: width and depth are the diameter, and the planar block in
    either direction rocks as the cylinder in a vertical plane through its axis (a homogeneous solid cylinder's
    ``cm_height = H/2`` and ``radius_of_gyration = sqrt(d²/16 + H²/12)`` unless given); written back as it was read.
    A cylinder row with a width, or a box row without one, is refused naming the file, line and column."""
    import math

    from opsrock.inventory.items import item_cells, read_inventory, write_inventory

    path = tmp_path / "round.csv"
    path.write_text("id,description,height,shape,diameter,radius_of_gyration\n"
                    "o2,an oxygen cylinder,1.5,cylinder,0.23,\n"
                    "drum,a steel drum,0.9,cylinder,0.6,0.3\n")
    o2, drum = read_inventory(path).items
    assert (o2.shape, o2.width, o2.depth) == ("cylinder", 0.23, 0.23)
    for direction in ("1", "2"):
        block = o2.planar_block(direction)
        assert block.width == 0.23 and block.h_cm == 0.75
        assert block.r_gyration == pytest.approx(math.sqrt(0.23**2 / 16 + 1.5**2 / 12), rel=1e-12)
    assert drum.planar_block("1").r_gyration == 0.3  # given: kept
    assert item_cells(o2)["diameter"] == 0.23 and "width" not in item_cells(o2)
    back = read_inventory(write_inventory(read_inventory(path), tmp_path / "back.csv")).items
    assert back == (o2, drum)
    for text, column in (("id,description,width,height,shape,diameter\no2,x,0.2,1.5,cylinder,0.23\n", "width"),
                         ("id,description,height,shape\no2,x,1.5,cylinder\n", "diameter"),
                         ("id,description,depth,height\nbox,x,0.5,1.5\n", "width"),
                         ("id,description,height,shape,diameter\no2,x,1.5,barrel,0.5\n", "shape")):
        (tmp_path / "bad.csv").write_text(text)
        with pytest.raises(InputError, match=column):
            read_inventory(tmp_path / "bad.csv")
