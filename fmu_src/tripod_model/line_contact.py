"""The needle's line contact coefficient from its length, Eq. (17) and Table 1 (the
roller-groove point contact, Eqs. (13)-(16), is reduced_model.hertz).  SI units; plain Python
(the set-up imports it where numba is not loaded).
"""


def needle_line_stiffness(l_needle):
    """Needle line contact, Eq. (17) / Table 1: delta = 3.8e-5 (N_s f)^0.9 / l^0.8 [mm, N].

    Returns C_line [N/m^(10/9)] with the force on the whole needle f_needle = C_line delta^(10/9)
    (the N_s spheres of one needle share the line contact).
    """
    l_mm = l_needle * 1e3
    # whole-needle force P = N_s f: delta_mm = 3.8e-5 P^0.9 / l^0.8  ->  P = (delta_mm l^0.8/3.8e-5)^(1/0.9)
    c_mm = (l_mm ** 0.8 / 3.8e-5) ** (1.0 / 0.9)            # N / mm^(10/9)
    return c_mm * (1e3) ** (10.0 / 9.0)                     # N / m^(10/9)
