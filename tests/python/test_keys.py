"""rotbeam.keys(): the key table, as `rotbeam keys --json` lists it."""
import rotbeam


def test_keys_lists_every_config_key_in_order_with_its_default():
    keys = rotbeam.keys()
    assert [k["name"] for k in keys] == rotbeam.config_keys()
    by_name = {k["name"]: k for k in keys}
    assert list(by_name["beam.length_m"]) == ["name", "type", "unit", "default", "unset", "allowed", "doc"]
    assert by_name["beam.length_m"]["default"] == 0.0635 and by_name["beam.length_m"]["unit"] == "m"
    assert by_name["beam.modes"]["type"] == "integer" and by_name["beam.modes"]["default"] == 5
    assert by_name["impact.restitution"]["default"] == "yigit"
    assert by_name["simulation.revolutions"]["unset"] == "none (one pass)"
    assert by_name["brush.seed"]["default"] == 1
