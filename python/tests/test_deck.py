"""visco2d.deck: a card value, a card word, the integrator card."""
import pytest

from visco2d import deck

DECK = """TITLE a drop
MESH SPHERE R=0.03 LEVEL=3   # LEVEL=9 in a comment stays
TIME DT=1e-5 TEND=4e-3
PLATE Z=0 STICK
END
"""


def test_card_value_only_on_its_card():
    text = deck.set_card_value(DECK, "MESH", "LEVEL", 2)
    assert "MESH SPHERE R=0.03 LEVEL=2   # LEVEL=9 in a comment stays" in text
    assert text.replace("LEVEL=2", "LEVEL=3") == DECK


def test_card_value_missing_card_names_it():
    with pytest.raises(ValueError, match="GRAVITY ... G="):
        deck.set_card_value(DECK, "GRAVITY", "G", 9.8)


def test_card_word():
    assert "PLATE Z=0 SLIP" in deck.set_card_word(DECK, "PLATE", "STICK", "SLIP")
    with pytest.raises(ValueError):
        deck.set_card_word(DECK, "PLATE", "SLIP", "STICK")


def test_integrator_added_before_time_then_replaced():
    once = deck.set_integrator(DECK, deck.INTEGRATOR_CARDS["NEWMARK"])
    assert "INTEGRATOR NEWMARK BETA=0.25 GAMMA=0.5\nTIME DT=1e-5" in once
    twice = deck.set_integrator(once, deck.INTEGRATOR_CARDS["BATHE"])
    assert "INTEGRATOR BATHE\nTIME" in twice and "NEWMARK" not in twice
