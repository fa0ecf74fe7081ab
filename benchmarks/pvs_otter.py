# MIT License
#
# Copyright (c) 2018 The Python Packaging Authority
#
# Permission is hereby granted, free of charge, to any person obtaining a copy
# of this software and associated documentation files (the "Software"), to deal
# in the Software without restriction, including without limitation the rights
# to use, copy, modify, merge, publish, distribute, sublicense, and/or sell
# copies of the Software, and to permit persons to whom the Software is
# furnished to do so, subject to the following conditions:
#
# The above copyright notice and this permission notice shall be included in all
# copies or substantial portions of the Software.
#
# THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
# IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
# FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
# AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
# LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
# OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
# SOFTWARE.
"""Vendored Otter USV time step from Fossen's Python Vehicle Simulator (PVS).

BENCHMARK ANCHOR ONLY -- not used by boatsim's simulation code.

Source: https://github.com/cybergalactic/PythonVehicleSimulator at commit
c717e073d7a839dcb5956cf20c595132f1fa249a (2025-05-13): vehicles/otter.py
(otter.__init__, dynamics, controlAllocation) and lib/gnc.py (helpers below).
Original author: Thor I. Fossen.  Licence above: PVS LICENSE text verbatim.

The arithmetic is deliberately kept identical to PVS (same numpy calls, same
per-step allocations, no optimisation) so that its per-step cost serves as a
reference point.  Removed: comments, docstrings, headingAutopilot/stepInput
methods and the m2c 3-DOF branch (the instance attributes are all kept).
`run` does the per-step work of PVS's lib/mainLoop.simulate() (dynamics +
attitudeEuler) with a constant propeller command, without simulate()'s
np.append/np.vstack logging.  Sample time 0.02 s (PVS main.py default).
"""
import math

import numpy as np

SAMPLE_TIME = 0.02  # PVS main.py default

# ---------------------------------------------------------------- lib/gnc.py
def sat(x, x_min, x_max):
    if x > x_max:
        x = x_max
    elif x < x_min:
        x = x_min
    return x

def Smtrx(a):
    S = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return S

def Hmtrx(r):
    H = np.identity(6,float)
    H[0:3, 3:6] = Smtrx(r).T
    return H

def Rzyx(phi,theta,psi):
    cphi = math.cos(phi)
    sphi = math.sin(phi)
    cth  = math.cos(theta)
    sth  = math.sin(theta)
    cpsi = math.cos(psi)
    spsi = math.sin(psi)
    R = np.array([
        [ cpsi*cth, -spsi*cphi+cpsi*sth*sphi, spsi*sphi+cpsi*cphi*sth ],
        [ spsi*cth,  cpsi*cphi+sphi*sth*spsi, -cpsi*sphi+sth*spsi*cphi ],
        [ -sth,      cth*sphi,                 cth*cphi ] ])
    return R

def Tzyx(phi,theta):
    cphi = math.cos(phi)
    sphi = math.sin(phi)
    cth  = math.cos(theta)
    sth  = math.sin(theta)
    try:
        T = np.array([
            [ 1,  sphi*sth/cth,  cphi*sth/cth ],
            [ 0,  cphi,          -sphi],
            [ 0,  sphi/cth,      cphi/cth] ])
    except ZeroDivisionError:
        print ("Tzyx is singular for theta = +-90 degrees." )
    return T

def attitudeEuler(eta,nu,sampleTime):
    p_dot   = np.matmul( Rzyx(eta[3], eta[4], eta[5]), nu[0:3] )
    v_dot   = np.matmul( Tzyx(eta[3], eta[4]), nu[3:6] )
    eta[0:3] = eta[0:3] + sampleTime * p_dot
    eta[3:6] = eta[3:6] + sampleTime * v_dot
    return eta

def m2c(M, nu):  # 6-DOF branch only (the Otter always passes len(nu) == 6)
    M = 0.5 * (M + M.T)
    if (len(nu) == 6):
        M11 = M[0:3,0:3]
        M12 = M[0:3,3:6]
        M21 = M12.T
        M22 = M[3:6,3:6]
        nu1 = nu[0:3]
        nu2 = nu[3:6]
        dt_dnu1 = np.matmul(M11,nu1) + np.matmul(M12,nu2)
        dt_dnu2 = np.matmul(M21,nu1) + np.matmul(M22,nu2)
        C = np.zeros( (6,6) )
        C[0:3,3:6] = -Smtrx(dt_dnu1)
        C[3:6,0:3] = -Smtrx(dt_dnu1)
        C[3:6,3:6] = -Smtrx(dt_dnu2)
    return C

def Hoerner(B,T):
    DATA1 = np.array([
        0.0109,0.1766,0.3530,0.4519,0.4728,0.4929,0.4933,0.5585,0.6464,0.8336,
        0.9880,1.3081,1.6392,1.8600,2.3129,2.6000,3.0088,3.4508, 3.7379,4.0031])
    DATA2 = np.array([
        1.9661,1.9657,1.8976,1.7872,1.5837,1.2786,1.2108,1.0836,0.9986,0.8796,
        0.8284,0.7599,0.6914,0.6571,0.6307,0.5962,0.5868,0.5859,0.5599,0.5593])
    CY_2D = np.interp( B / (2 * T), DATA1, DATA2 )
    return CY_2D

def crossFlowDrag(L,B,T,nu_r):
    rho = 1026
    n = 20
    dx = L/20
    Cd_2D = Hoerner(B,T)
    Yh = 0
    Nh = 0
    xL = -L/2
    for i in range(0,n+1):
        v_r = nu_r[1]
        r = nu_r[5]
        Ucf = abs(v_r + xL * r) * (v_r + xL * r)
        Yh = Yh - 0.5 * rho * T * Cd_2D * Ucf * dx
        Nh = Nh - 0.5 * rho * T * Cd_2D * xL * Ucf * dx
        xL += dx
    tau_crossflow = np.array([0, Yh, 0, 0, 0, Nh],float)
    return tau_crossflow

# ------------------------------------------------------- vehicles/otter.py
class otter:
    def __init__(self, controlSystem="stepInput", r=0, V_current=0,
                 beta_current=0, tau_X=120):  # only the stepInput mode is vendored
        D2R = math.pi / 180
        self.g, rho = 9.81, 1025
        self.controlDescription = "Step inputs for n1 and n2"
        self.ref, self.V_c, self.beta_c = r, V_current, beta_current * D2R
        self.controlMode, self.tauX = "stepInput", tau_X
        self.T_n, self.L, self.B = 0.1, 2.0, 1.08
        self.nu = np.array([0, 0, 0, 0, 0, 0], float)
        self.u_actual = np.array([0, 0], float)
        self.name = "Otter USV (see 'otter.py' for more details)"
        self.controls = ["Left propeller shaft speed (rad/s)",
                         "Right propeller shaft speed (rad/s)"]
        self.dimU = len(self.controls)
        m, self.mp = 55.0, 25.0
        self.m_total = m + self.mp
        self.rp = np.array([0.05, 0, -0.35], float)
        rg = np.array([0.2, 0, -0.2], float)
        rg = (m * rg + self.mp * self.rp) / (m + self.mp)
        self.S_rg, self.H_rg, self.S_rp = Smtrx(rg), Hmtrx(rg), Smtrx(self.rp)
        R44, R55, R66 = 0.4 * self.B, 0.25 * self.L, 0.25 * self.L
        T_sway, T_yaw, Umax = 1.0, 1.0, 6 * 0.5144
        self.B_pont, y_pont, Cw_pont, Cb_pont = 0.25, 0.395, 0.75, 0.4
        nabla = (m + self.mp) / rho
        self.T = nabla / (2 * Cb_pont * self.B_pont * self.L)
        Ig_CG = m * np.diag(np.array([R44 ** 2, R55 ** 2, R66 ** 2]))
        self.Ig = Ig_CG - m * self.S_rg @ self.S_rg - self.mp * self.S_rp @ self.S_rp
        self.l1, self.l2 = -y_pont, y_pont
        self.k_pos, self.k_neg = 0.02216 / 2, 0.01289 / 2
        self.n_max = math.sqrt((0.5 * 24.4 * self.g) / self.k_pos)
        self.n_min = -math.sqrt((0.5 * 13.6 * self.g) / self.k_neg)
        MRB_CG = np.zeros((6, 6))
        MRB_CG[0:3, 0:3] = (m + self.mp) * np.identity(3)
        MRB_CG[3:6, 3:6] = self.Ig
        MRB = self.H_rg.T @ MRB_CG @ self.H_rg
        Xudot, Yvdot, Zwdot = -0.1 * m, -1.5 * m, -1.0 * m
        Kpdot, Mqdot, Nrdot = (-0.2 * self.Ig[0, 0], -0.8 * self.Ig[1, 1],
                               -1.7 * self.Ig[2, 2])
        self.MA = -np.diag([Xudot, Yvdot, Zwdot, Kpdot, Mqdot, Nrdot])
        self.M = MRB + self.MA
        self.Minv = np.linalg.inv(self.M)
        Aw_pont = Cw_pont * self.L * self.B_pont
        I_T = (2 * (1 / 12) * self.L * self.B_pont ** 3
               * (6 * Cw_pont ** 3 / ((1 + Cw_pont) * (1 + 2 * Cw_pont)))
               + 2 * Aw_pont * y_pont ** 2)
        I_L = 0.8 * 2 * (1 / 12) * self.B_pont * self.L ** 3
        KB = (1 / 3) * (5 * self.T / 2 - 0.5 * nabla / (self.L * self.B_pont))
        BM_T, BM_L = I_T / nabla, I_L / nabla
        KM_T, KM_L = KB + BM_T, KB + BM_L
        KG = self.T - rg[2]
        GM_T, GM_L = KM_T - KG, KM_L - KG
        G33, G44, G55 = (rho * self.g * (2 * Aw_pont), rho * self.g * nabla * GM_T,
                         rho * self.g * nabla * GM_L)
        G_CF = np.diag([0, 0, G33, G44, G55, 0])
        H = Hmtrx(np.array([-0.2, 0.0, 0.0]))  # LCF = -0.2
        self.G = H.T @ G_CF @ H
        w3, w4, w5 = (math.sqrt(G33 / self.M[2, 2]), math.sqrt(G44 / self.M[3, 3]),
                      math.sqrt(G55 / self.M[4, 4]))
        Xu, Yv = -24.4 *self. g / Umax, -self.M[1, 1]  / T_sway
        Zw, Kp = -2 * 0.3 * w3 * self.M[2, 2], -2 * 0.2 * w4 * self.M[3, 3]
        Mq, Nr = -2 * 0.4 * w5 * self.M[4, 4], -self.M[5, 5] / T_yaw
        self.D = -np.diag([Xu, Yv, Zw, Kp, Mq, Nr])
        B = self.k_pos * np.array([[1, 1], [-self.l1, -self.l2]])
        self.Binv = np.linalg.inv(B)
        # Unused autopilot states, kept so the instance has PVS's 45 attributes
        # (>30 un-shares the instance __dict__ in CPython, slower self.x reads).
        self.e_int, self.wn, self.zeta = 0, 2.5, 1
        self.r_max = 10 * math.pi / 180
        self.psi_d, self.r_d, self.a_d = 0, 0, 0
        self.wn_d, self.zeta_d = 0.5, 1

    def dynamics(self, eta, nu, u_actual, u_control, sampleTime):
        n = np.array([u_actual[0], u_actual[1]])
        u_c = self.V_c * math.cos(self.beta_c - eta[5])
        v_c = self.V_c * math.sin(self.beta_c - eta[5])
        nu_c = np.array([u_c, v_c, 0, 0, 0, 0], float)
        Dnu_c = np.array([nu[5]*v_c, -nu[5]*u_c, 0, 0, 0, 0],float)
        nu_r = nu - nu_c
        CRB_CG = np.zeros((6, 6))
        CRB_CG[0:3, 0:3] = self.m_total * Smtrx(nu[3:6])
        CRB_CG[3:6, 3:6] = -Smtrx(np.matmul(self.Ig, nu[3:6]))
        CRB = self.H_rg.T @ CRB_CG @ self.H_rg
        CA = m2c(self.MA, nu_r)
        C = CRB + CA
        R = Rzyx(eta[3], eta[4], eta[5])
        f_payload = np.matmul(R.T, np.array([0, 0, self.mp * self.g], float))
        m_payload = np.matmul(self.S_rp, f_payload)
        g_0 = np.array([ f_payload[0],f_payload[1],f_payload[2],
                         m_payload[0],m_payload[1],m_payload[2] ])
        thrust = np.zeros(2)
        for i in range(0, 2):
            n[i] = sat(n[i], self.n_min, self.n_max)
            if n[i] > 0:
                thrust[i] = self.k_pos * n[i] * abs(n[i])
            else:
                thrust[i] = self.k_neg * n[i] * abs(n[i])
        tau = np.array([thrust[0] + thrust[1], 0, 0, 0, 0,
                        -self.l1 * thrust[0] - self.l2 * thrust[1]])
        tau_damp = -np.matmul(self.D, nu_r)
        tau_damp[5] = tau_damp[5] - 10 * self.D[5, 5] * abs(nu_r[5]) * nu_r[5]
        tau_crossflow = crossFlowDrag(self.L, self.B_pont, self.T, nu_r)
        sum_tau = (tau + tau_damp + tau_crossflow
                   - np.matmul(C, nu_r) - np.matmul(self.G, eta) + g_0)
        nu_dot = Dnu_c + np.matmul(self.Minv, sum_tau)
        n_dot = (u_control - n) / self.T_n
        nu = nu + sampleTime * nu_dot
        n = n + sampleTime * n_dot
        u_actual = np.array(n, float)
        return nu, u_actual

    def controlAllocation(self, tau_X, tau_N):
        tau = np.array([tau_X, tau_N])
        u_alloc = np.matmul(self.Binv, tau)
        n1 = np.sign(u_alloc[0]) * math.sqrt(abs(u_alloc[0]))
        n2 = np.sign(u_alloc[1]) * math.sqrt(abs(u_alloc[1]))
        return n1, n2

# ------------------------------------------------------------- benchmark
def cruise_command(vehicle, tau_X=None):
    """Both propellers at the speed giving surge force tau_X (default 120 N
    -> 73.59 rad/s each)."""
    tX = vehicle.tauX if tau_X is None else tau_X
    return np.array(vehicle.controlAllocation(tX, 0.0), float)

def run(steps: int, sampleTime: float = SAMPLE_TIME, u_control=None) -> np.ndarray:
    """PVS simulate() per-step work (dynamics + attitudeEuler) for `steps`
    steps with a constant propeller command; returns the final eta."""
    vehicle = otter()
    if u_control is None:
        u_control = cruise_command(vehicle)
    eta = np.array([0, 0, 0, 0, 0, 0], float)
    nu = vehicle.nu
    u_actual = vehicle.u_actual
    for i in range(steps):
        [nu, u_actual] = vehicle.dynamics(eta, nu, u_actual, u_control, sampleTime)
        eta = attitudeEuler(eta, nu, sampleTime)
    return eta

