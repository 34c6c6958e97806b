"""Array layouts shared by the compiled kernel and the Python around it: what each slot of the
parameter, state, output and operating-point vectors holds.  Plain Python (no numba), so the
model's set-up reads them without importing numba.
"""
from collections import namedtuple

from reduced_model import scene

# --- parameter vector layout (float64 array P) ---
# a new slot: its name before P_LEN (the numbering follows; *_ takes the unused rest)
(P_S, P_R_ROLLER, P_R_GROOVE, P_M_ROLLER, P_IS, P_K, P_A1, P_MU_GROOVE, P_VST_OP, P_PITCH,
 P_YAW, P_ROLL, P_AXIAL, P_TRAVERSE, P_FRICTION_GROOVE, P_SPIN_MOMENT, P_BEARING, P_MU_NEEDLE,
 P_MU_ROLLING, P_FRICTION_NEEDLE, P_ROLLING_RESISTANCE, P_KN, P_R_BORE, P_QSUM,
 P_NEEDLE_CLEARANCE, P_INTEGRATOR, P_LT, P_IT, P_STEP_TOLERANCE, P_HMAX, P_V_ST,
 P_MAX_SUBSTEP, P_VP, P_CONTACT_DAMPING, P_ROW_DAMPING, P_DF, P_FLANK, P_HFREE, P_RINGA,
 P_NEWTON_PASSES, P_NEWTON_TOL, P_SPIDER, P_SPIDER_MASS, P_SPIDER_INERTIA, P_NROW, P_KN1, P_TOLERANCE,
 P_NEEDLE_AXIAL_CLEARANCE, P_LEN,
 *_) = range(128)
# The slots named after a parameter hold its value (roller_setup.COPIED, FLAGS); the others
# what the set-up derives (roller_setup.kernel_params) or the operating point does: P_VST_OP,
# P_HMAX the transition velocity and the largest adaptive substep the operating point derived
# from v_st and max_substep (0: automatic; oppoint.py); P_VP: the plunge speed [m/s] of the
# step (an input, there for the line kinematics); P_DF: the pressing load's relative change at
# this communication point (oppoint.derive; the lumped row's offset moves with it); P_FLANK:
# how far each flank's arc centre sits off the track's mid-plane [m] (contact.flank_centre; 0:
# one cylinder); P_HFREE: the generalized-alpha substep without the ring's bound [s] (0: none),
# P_RINGA: the slide's acceleration below which the ring counts as quiet [m/s^2]
# (oppoint.derive, genalpha.ga_steps); P_NROW, P_KN1: the lumped row's needles and each one's
# Eq. (17) constant over its two races in series (oppoint.row_sums); P_STEP_TOLERANCE: step_tolerance or its automatic value
# --- the bearings and integrators: the values of the parameters `bearing` and `integrator`
# as named in reduced_model/scene.py, as the floats P holds; the kernel tests P[P_BEARING],
# P[P_INTEGRATOR] against these
BEAR_IDEAL, BEAR_LUMPED, BEAR_RESOLVED = (float(b) for b in (
    scene.BEARING_IDEAL, scene.BEARING_LUMPED, scene.BEARING_RESOLVED))
INT_EULER = float(scene.INTEGRATOR_EULER)                # linearly implicit Euler
INT_EXTRAPOLATED = float(scene.INTEGRATOR_EXTRAPOLATED)  # Richardson-extrapolated (steplib.extrapolated_step)
INT_EXPLICIT = float(scene.INTEGRATOR_EXPLICIT)   # explicit (symplectic) Euler, for comparison
INT_ADAPTIVE = float(scene.INTEGRATOR_ADAPTIVE)   # extrapolated, substep by its error estimate
INT_DEFAULT = float(scene.INTEGRATOR_DEFAULT)     # generalized-alpha (ideal, lumped); BDF2 (resolved)
# --- state vector layout (float64 array Y) ---
# whirl angle, slide along the trunnion axis u, its rate, absolute spin rate about the axis,
# radial offset of the roller from the trunnion axis along x (lumped bearing), its rate;
# lumped bearing only: radial offset w along e2 = a x e1 and tilts b1, b2 about e1, e2
# (e1 = the pressing direction normal to the trunnion axis), with their rates
# Y_PL: the plunge [m], the spider's travel along the groove (the integral of the plunge speed)
(Y_X, Y_U, Y_UD, Y_OM, Y_E, Y_ED, Y_W, Y_WD, Y_B1, Y_B1D, Y_B2, Y_B2D, Y_PL, Y_LEN) = range(14)
NV = 6   # velocity unknowns of the implicit step: ud, om, wd, b1d, b2d, (ed: resolved bearing)
# the roller's velocity unknowns in Y, in the order of the implicit steps' systems, the
# positions they move (-1: the spin angle, which nothing depends on), and whether they turn
# (scaled by r against v_st)
V_VEL = (Y_UD, Y_OM, Y_WD, Y_B1D, Y_B2D, Y_ED)
V_POS = (Y_U, -1, Y_W, Y_B1, Y_B2, Y_E)
V_ROT = (0.0, 1.0, 0.0, 1.0, 1.0, 0.0)
# --- the roller-groove contact's result res (contact.groove_contact), forces on the roller ---
# force [N], moment about the centre [N m], normal n, f_n [N], tangential slip v_t [m/s], |v_t|,
# g = tanh(3 |v_t| / v_st), the friction slope d(mu f_n g)/d|v_t| [N s/m], contact point [m]
(R_FX, R_FY, R_FZ, R_MX, R_MY, R_MZ, R_NX, R_NY, R_NZ, R_FN, R_VTX, R_VTY, R_VTZ, R_SLIP,
 R_G, R_SLOPE, R_PX, R_PY, R_PZ, R_LEN) = range(20)
# --- the trunnion line L (contact.line_kinematics) at whirl angle x ---
# its axis a and da/dt, d2a/dt2; the origin Q's travel along the groove Qz with dQz/dt (the
# plunge speed included) and d2Qz/dt2; the trunnion's material velocity along a and its spin
# rate about a; then the key (x, w, theta, plunge speed) it was computed for (NaN: none)
(L_AX, L_AY, L_AZ, L_ADX, L_ADY, L_ADZ, L_AAX, L_AAY, L_AAZ, L_QZ, L_QZD, L_QZDD, L_VAX,
 L_SPIN, L_KX, L_KW, L_KTH, L_KVP, L_LEN) = range(19)
# --- the integrators' history hs, carried from step to step ---
# H_SUB: the adaptive substep (BDF2: the previous substep) [s]; H_TAKEN, H_REJECTED: substeps
# counted; H_GA: the generalized-alpha history's state (genalpha.py; BDF2: its previous state
# valid); H_FALLBACK: steps handed to the adaptive substeps; H_ACC..: the algorithmic
# accelerations of the NV unknowns (generalized-alpha); H_FACC..: their accelerations from the
# forces at the end of a restart step (genalpha.GA_AFTER_RESTART); H_RING: the roller's ring
# (RING_OPEN or RING_QUIET, genalpha.ga_steps); H_PASSES: BDF2's Newton passes after the first,
# counted (the needle-resolved bearing's; it has no generalized-alpha accelerations to keep)
H_SUB, H_TAKEN, H_REJECTED, H_GA, H_FALLBACK, H_ACC = range(6)
H_FACC = H_ACC + NV
H_RING = H_FACC + NV
# the step's budget (budget.py): H_FAIL why the last step stopped short (FAIL_*; 0: it did
# not), H_FAIL_DONE the share of the adaptive substeps' span done then and H_FAIL_H their
# substep [s] (FAIL_LONG, kernel.run_substeps: the step's length [s] and substep);
# H_USE_TRIES the largest share of a call's budget of tries used so far, H_USE_FLOOR the
# largest ratio floor / substep tried (both < 1 while the budget never binds)
H_FAIL, H_FAIL_DONE, H_FAIL_H, H_USE_TRIES, H_USE_FLOOR = range(H_RING + 1, H_RING + 6)
# H_JUMPW: the share of a full restart the inputs' last change takes, in [0, 1]
# (genalpha.inputs_jumped: the restart step's weight, or the fresh forces' after one)
H_JUMPW = H_USE_FLOOR + 1
H_LEN = H_JUMPW + 1
FAIL_NONE, FAIL_ESTIMATE, FAIL_FLOOR, FAIL_TRIES, FAIL_LONG = 0.0, 1.0, 2.0, 3.0, 4.0
H_PASSES = H_ACC
RING_OPEN, RING_QUIET = 0.0, 1.0   # hs[H_RING]: resolved (the start's value), quiet
# --- output vector layout ---
(O_FX, O_FY, O_FZ, O_CY, O_CZ, O_SLIP, O_SPIN, O_FN, O_X, O_PL, O_LEN) = range(11)
# generalized-alpha work array GW (NV + 8 rows of NV): rows after the unknowns' own
(W_R, W_A, W_D, W_RT, W_AT, W_M, W_A0, W_S) = range(NV, NV + 8)

# --- needle-resolved bearing (needles.py) ---
N_F = 11   # floats per needle in the state vector
# needle parameter vector NP
(N_N, N_NS, N_RN, N_RT, N_RBR, N_LN, N_MN, N_I1, N_I3, N_CS, N_DC, N_ZAX, N_HW,
 N_MU, N_MUR, N_FRIC, N_ROLLR, N_LEN) = range(18)
# diagnostics per needle, ND[j, :]
(D_BORE, D_TRUN, D_NEIGH, D_FLANGE, D_R1, D_R2, D_R3, D_LEN) = range(8)
# D_BORE, D_TRUN, D_NEIGH, D_FLANGE: summed normal loads [N] on the bore, trunnion, next
# needle and flange/retainer; D_R1..3: force of the needle on the roller in T (e1, e2, e3) [N]

# --- the communication step's operating point ---
# the operating point it runs at (oppoint.derive): inputs theta, omega, F_press, torque, the
# plunge speed OP_VP and the step dt; what they set (pressing load per roller, pressing offset,
# substep and count); the inputs it was derived at (OP_KEY: six slots, theta, omega, F_press,
# torque, dt, plunge speed); OP_NOSTEP > 0: outputs only, no substep;
# OP_NROLL: 0 in a roller's own OP; n > 0 in the header row of a joint's n rollers (kernel.step_joint)
(OP_THETA, OP_W, OP_F, OP_X0, OP_H, OP_N, OP_FP, OP_TQ, OP_DT, OP_NOSTEP, OP_VP,
 OP_KEY) = range(12)
OP_NROLL = OP_KEY + 6
# a joint's header row, spider = free (spider.py): the spider's coordinates q = (dX, dY [m],
# psi [rad]) off its kinematic pose (Eq. 5's orbit, untwisted) and their rates, whether they
# are set (OP_SP_SET), the pressing loads the trunnions carried at the step's end [N] and the
# forces on the spider then (the rollers' and the torque's, generalized: N, N, N m)
(OP_SP_QX, OP_SP_QY, OP_SP_PSI, OP_SP_VX, OP_SP_VY, OP_SP_VPSI, OP_SP_SET, OP_SP_F1, OP_SP_F2,
 OP_SP_F3, OP_SP_GX, OP_SP_GY, OP_SP_GPSI) = range(OP_NROLL + 1, OP_NROLL + 14)
OP_LEN = OP_SP_GPSI + 1
OUTPUT_NAMES = ("Fx", "Fy", "Fz", "Fz_mod", "dFx", "contact_y", "contact_z", "slip_speed",
                "roller_spin", "Fz_joint", "Fz_2", "Fz_3", "whirl_angle",
                "Fx_2", "Fy_2", "contact_y_2", "contact_z_2",
                "Fx_3", "Fy_3", "contact_y_3", "contact_z_3",
                "F_housing_x", "F_housing_y", "T_housing", "F_roller", "plunge",
                "spider_x", "spider_y", "F_roller_1", "F_roller_2", "F_roller_3")
N_OUT = len(OUTPUT_NAMES)
OUT_FZ_JOINT, OUT_FZ_2, OUT_FZ_3 = (OUTPUT_NAMES.index(n) for n in ("Fz_joint", "Fz_2", "Fz_3"))
OUT_FX_2 = OUTPUT_NAMES.index("Fx_2")   # the joint's outputs from here on (kernel.joint_into)
OUT_PLUNGE = OUTPUT_NAMES.index("plunge")
OUT_SPIDER_X = OUTPUT_NAMES.index("spider_x")   # then spider_y, F_roller_1..3 (kernel.spider_into)

# --- records passed through the kernel (numba takes namedtuples as typed records) ---
# the step's driving inputs: joint angle theta [rad], whirl rate w [rad/s], the trunnion
# axis' pressing offset x0 [m] (oppoint.derive; at the step's end) and its rate x0_rate [m/s]
# over the step (the needle-resolved bearing's ramp after a load change with BDF2,
# model.Roller.load_ramped; 0 otherwise)
Drive = namedtuple("Drive", "theta w x0 x0_rate")
# one roller's work arrays (model.ContactModel makes them): the trunnion line L (L_LEN), the
# contact's result res (R_LEN), two states Y1, Y2 (like Y), the slip sensitivities G (NV x 3),
# the implicit step's system A (NV x NV) and b (NV), the integrators' history hs (H_LEN), the
# generalized-alpha work rows GW (NV + 8 x NV)
Work = namedtuple("Work", "L res Y1 Y2 G A b hs GW")
# the needle-resolved bearing's parameters NP and work arrays (needle_setup.needle_work;
# needles.py, ring.py, rowsolve.py): sphere centres SP, each needle's system FN, AN, the roller's
# FR, AR, diagnostics ND, friction moments MOM, PM, the roller's standard system RS and moments
# MR, scratch normals gn, gn2, the neighbour coupling UN; the ring solve's CW, XW, S, T; the
# one-system step's roller-needle coupling BN and its moments PB, right-hand sides RH, the
# ring solve's XW7, T7 for seven of them, B' (BP), the open ring's Cholesky factors LF and
# flags ZF
NeedleWork = namedtuple("NeedleWork", "NP SP FN AN FR AR ND MOM gn PM RS UN MR gn2 CW XW S T "
                                      "BN PB RH XW7 T7 BP LF ZF")
