package io.etherware.pendulum.plant;

/**
 * The pendulum integrated by the classical fixed-step fourth-order Runge-Kutta method.
 *
 * <p>{@link #step(double)} advances by exactly {@link #stepNs()} holding the torque constant over
 * the step (the motor's zero-order hold); it allocates nothing. Not thread-safe: one owner (the
 * simulated DSP board) steps it; others read snapshots through that owner.
 */
public final class PendulumPlant {

    /** The default integration step, 0.5 ms. */
    public static final long DEFAULT_STEP_NS = 500_000L;

    private final PendulumDynamics dynamics;
    private final long stepNs;
    private final double stepS;
    private final double[] x = new double[PendulumState.SIZE];
    private final double[] k1 = new double[PendulumState.SIZE];
    private final double[] k2 = new double[PendulumState.SIZE];
    private final double[] k3 = new double[PendulumState.SIZE];
    private final double[] k4 = new double[PendulumState.SIZE];
    private final double[] stage = new double[PendulumState.SIZE];
    private long steps;

    /**
     * A plant at {@code initial} with the default 0.5 ms step.
     *
     * @param parameters the pendulum's parameters
     * @param initial    the state at time 0
     */
    public PendulumPlant(PendulumParameters parameters, PendulumState initial) {
        this(parameters, initial, DEFAULT_STEP_NS);
    }

    /**
     * A plant at {@code initial}.
     *
     * @param parameters the pendulum's parameters
     * @param initial    the state at time 0
     * @param stepNs     the integration step, 1 µs to 10 ms
     * @throws IllegalArgumentException when {@code stepNs} is out of range
     */
    public PendulumPlant(PendulumParameters parameters, PendulumState initial, long stepNs) {
        if (stepNs < 1_000L || stepNs > 10_000_000L) {
            throw new IllegalArgumentException("stepNs=" + stepNs
                    + ": must be between 1000 (1 µs) and 10000000 (10 ms); default "
                    + DEFAULT_STEP_NS);
        }
        this.dynamics = new PendulumDynamics(parameters);
        this.stepNs = stepNs;
        this.stepS = stepNs * 1e-9;
        initial.copyInto(x);
    }

    /**
     * Advances one step of {@link #stepNs()} with the torque held constant; allocation-free.
     *
     * @param torqueNm the motor torque u at joint 1 over the step, in N·m
     */
    public void step(double torqueNm) {
        double h = stepS;
        dynamics.derivative(x, torqueNm, k1);
        for (int i = 0; i < x.length; i++) {
            stage[i] = x[i] + 0.5 * h * k1[i];
        }
        dynamics.derivative(stage, torqueNm, k2);
        for (int i = 0; i < x.length; i++) {
            stage[i] = x[i] + 0.5 * h * k2[i];
        }
        dynamics.derivative(stage, torqueNm, k3);
        for (int i = 0; i < x.length; i++) {
            stage[i] = x[i] + h * k3[i];
        }
        dynamics.derivative(stage, torqueNm, k4);
        for (int i = 0; i < x.length; i++) {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
        steps++;
    }

    /**
     * The integration step.
     *
     * @return the step, in nanoseconds
     */
    public long stepNs() {
        return stepNs;
    }

    /**
     * Simulated time since construction or the last {@link #reset}.
     *
     * @return steps × step, in nanoseconds
     */
    public long timeNs() {
        return steps * stepNs;
    }

    /**
     * θ1, the arm angle.
     *
     * @return the angle in radians, multi-turn (not wrapped)
     */
    public double theta1Rad() {
        return x[PendulumState.THETA1];
    }

    /**
     * θ2, the pendulum angle.
     *
     * @return the angle in radians, 0 upright
     */
    public double theta2Rad() {
        return x[PendulumState.THETA2];
    }

    /**
     * The current state, as a new value; allocates.
     *
     * @return the state
     */
    public PendulumState state() {
        return PendulumState.of(x);
    }

    /**
     * Copies the state vector into an array without allocating.
     *
     * @param out receives {@code [θ1, θ̇1, θ2, θ̇2]} in its first {@value PendulumState#SIZE} entries
     * @throws IndexOutOfBoundsException when {@code out} is shorter than {@value PendulumState#SIZE}
     */
    public void copyState(double[] out) {
        System.arraycopy(x, 0, out, 0, x.length);
    }

    /**
     * Total mechanical energy of the current state (see {@link PendulumDynamics#energyJ}).
     *
     * @return the energy, in joules
     */
    public double energyJ() {
        return dynamics.energyJ(x);
    }

    /**
     * The dynamics being integrated.
     *
     * @return the dynamics, shareable between threads
     */
    public PendulumDynamics dynamics() {
        return dynamics;
    }

    /**
     * Puts the plant in a state and restarts its time at zero.
     *
     * @param state the new state
     */
    public void reset(PendulumState state) {
        state.copyInto(x);
        steps = 0;
    }
}
