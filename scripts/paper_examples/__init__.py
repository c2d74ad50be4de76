"""One module per numerical example of the paper; scripts/reproduce_paper.py drives them."""
