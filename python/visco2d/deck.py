"""Variants of a deck by text substitution: a card value (MESH SPHERE ... LEVEL=, TIME DT=),
a word of a card (PLATE ... STICK), the integrator card. The studies, the benchmarks and the
figures make their decks with these; visco2d-batch's placeholders (${name}) are its own
(visco2d.batch), because they substitute anywhere in the text, not on a named card."""
import re


def set_card_value(text, card, key, value):
    """Replace KEY=<value> on the one CARD line of a deck (comments untouched).

    Raises ValueError naming the card when the deck has not exactly one such line."""
    pattern = r"(?im)^(\s*%s\b[^\n#]*?\b%s\s*=\s*)\S+" % (card, key)
    new, count = re.subn(pattern, lambda match: match.group(1) + str(value), text)
    if count != 1:
        raise ValueError("expected one '%s ... %s=' card, found %d" % (card, key, count))
    return new


def set_card_word(text, card, word, replacement):
    """Replace the word WORD on the one CARD line that has it (e.g. PLATE ... STICK -> SLIP)."""
    pattern = r"(?im)^(\s*%s\b[^\n#]*?)\b%s\b" % (card, word)
    new, count = re.subn(pattern, lambda match: match.group(1) + replacement, text)
    if count != 1:
        raise ValueError("expected one '%s ... %s' card, found %d" % (card, word, count))
    return new


#: The integrators of the INTEGRATOR card as compared by visco2d.study and
#: visco2d.integrators: name -> the card (each method's usual parameters).
#: WILSON is the paper's (and every deck's default): its card is the deck's own.
INTEGRATOR_CARDS = {
    "WILSON": "INTEGRATOR WILSON THETA=1.4",
    "NEWMARK": "INTEGRATOR NEWMARK BETA=0.25 GAMMA=0.5",
    "HHT": "INTEGRATOR HHT ALPHA=0.05",
    "GENERALIZED_ALPHA": "INTEGRATOR GENERALIZED_ALPHA RHO_INF=0.8",
    "BATHE": "INTEGRATOR BATHE",
}


def set_integrator(text, card):
    """Replace the one WILSON or INTEGRATOR card of a deck by `card` (added before TIME if there is none)."""
    new, count = re.subn(r"(?im)^[ \t]*(WILSON|INTEGRATOR)\b[^\n]*$", card, text)
    if count == 1:
        return new
    if count == 0:
        new, count = re.subn(r"(?im)^([ \t]*TIME\b)", card + "\n" + r"\1", text, count=1)
        if count == 1:
            return new
    raise ValueError("expected at most one WILSON or INTEGRATOR card and a TIME card, found %d" % count)

