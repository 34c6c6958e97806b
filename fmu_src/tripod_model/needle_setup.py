"""The needle-resolved bearing's arrays (model.ContactModel makes them): its parameter vector
(roller_setup.needle_params) and work arrays (layout.NeedleWork).
"""
import numpy as np

from . import layout as K
from .roller_setup import needle_params


def needle_work(T, n, ns):
    """The parameter vector NP and work arrays of n needles of ns spheres each
    (layout.NeedleWork; needles.py) for the table's values T (roller_setup.py)."""
    NP = np.zeros(K.N_LEN)
    needle_params(T, NP)
    z = np.zeros
    return K.NeedleWork(
        NP=NP, SP=z((n, ns, 3)), FN=z((n, 6)), AN=z((n, 6, 6)), FR=z(6), AR=z((6, 6)),
        ND=z((n, K.D_LEN)), MOM=z((n, 10)), gn=z(6), PM=z((n, 10)), RS=z((6, 13)),
        UN=z((n, 6, 6)), MR=z(10), gn2=z(6), CW=z((n, 6, 6)), XW=z((n, 6, 7)), S=z((6, 6)),
        T=z((6, 13)), BN=z((n, 6, 6)), PB=z((n, 10)), RH=z((n, 6, 7)), XW7=z((n, 6, 13)),
        T7=z((6, 19)), BP=z((n, 6, 6)), LF=z((n, 6, 6)), ZF=z(n))
