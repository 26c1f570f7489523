/*---------------------------------------------------------------------------*\
    cosimFoam: the OpenFOAM side. Owns the case (time, mesh, fields), places
    the parcels, samples the gas at them and advances the gas one CFD step
    (PIMPLE) with the parcels' momentum exchange and precursor sink.
    The equations are in createFields.H, UEqn.H, pEqn.H, rhoEqn.H, YEqn.H.
\*---------------------------------------------------------------------------*/

#include "GasDomain.h"

#include "fvCFD.H"
#include "pimpleControl.H"
#include "constrainHbyA.H"
#include "constrainPressure.H"
#include "fixedFluxPressureFvPatchScalarField.H"
#include "gravityMeshObject.H"
#include "zeroGradientFvPatchFields.H"
#include "fixedValueFvPatchFields.H"
#include "wallPolyPatch.H"
#include "physicoChemicalConstants.H"
#include "ParcelDeposition.H"
#include "cellValuesOnBoundary.H"
#include "bedConsistentGradient.H"
#include "reconstructFaceFlux.H"

#include <chrono>
#include <stdexcept>

#include "cosim/util/errors.h"

namespace cosim::foam
{

namespace
{

// OpenFOAM errors become solver errors (cosim/util/errors.h) carrying OpenFOAM's own message
template<class F>
auto guarded(const char* what, F&& f) -> decltype(f())
{
    try
    {
        return f();
    }
    catch (const Foam::error& e)
    {
        throw ::cosim::SolverError
        (
            std::string("OpenFOAM error while ") + what + ": " + e.message()
        );
    }
}

bool hasPatch(const std::vector<std::string>& names, const Foam::word& patchName)
{
    for (const auto& n : names)
    {
        if (Foam::word(n) == patchName)
        {
            return true;
        }
    }
    return false;
}

} // namespace


using namespace Foam;

class FoamGasDomain : public GasDomain
{
    GasSettings settings_;

    // Never deleted: Foam::argList's destructor ends the process (UPstream::exit), which
    // must not happen before the session has sent its Goodbye or Error.
    argList* args_ = nullptr;
    autoPtr<Time> runTime_;
    autoPtr<fvMesh> mesh_;
    autoPtr<pimpleControl> pimple_;

    autoPtr<dimensionedScalar> psi_;
    autoPtr<dimensionedScalar> mu_;
    autoPtr<volScalarField> p_;
    autoPtr<volVectorField> U_;
    autoPtr<volScalarField> rho_;
    autoPtr<volScalarField> eps_;
    autoPtr<scalarField> epsPlaced_;
    autoPtr<volScalarField> epsRho_;
    autoPtr<surfaceScalarField> phi_;
    autoPtr<volScalarField> Kexchange_;
    autoPtr<volVectorField> KUp_;
    autoPtr<volScalarField> resistance_;  // A/eps^2 of the last pressure solve (pEqn.H)
    autoPtr<volScalarField> Y_;
    autoPtr<volScalarField> epsRhoY_;
    autoPtr<volScalarField> sinkCoeff_;

    autoPtr<Foam::cosim::ParcelDeposition> parcels_;
    List<vector> particleVelocity_;
    bool advanced_ = false;
    bool resumedOldTimes_ = false;  // createFields.H read the checkpoint's old-time fields

public:

    FoamGasDomain(int argc, char** argv, const GasSettings& settings)
    :
        settings_(settings)
    {
        FatalError.throwExceptions();
        FatalIOError.throwExceptions();

        guarded("reading the case", [&]
        {
            args_ = new argList(argc, argv);
            if (!args_->checkRootCase())
            {
                FatalError.exit();
            }
            runTime_.reset(new Time(Time::controlDictName, *args_));
            Time& runTime = runTime_();

            mesh_.reset(new fvMesh
            (
                IOobject(fvMesh::defaultRegion, runTime.timeName(), runTime, IOobject::MUST_READ)
            ));
            fvMesh& mesh = mesh_();
            pimple_.reset(new pimpleControl(mesh));

            checkSchemes(mesh);
            checkPatches(mesh, settings_.inlet_patches, "inlet_patches");
            checkPatches(mesh, settings_.outlet_patches, "outlet_patches");

            #include "createFields.H"

            parcels_.reset(new Foam::cosim::ParcelDeposition(mesh, settings_.voidage_divisions));
            return 0;
        });
    }

    // Patch names in the options must be patches of the mesh
    static void checkPatches
    (
        const fvMesh& mesh,
        const std::vector<std::string>& names,
        const char* key
    )
    {
        for (const auto& n : names)
        {
            if (mesh.boundaryMesh().findPatchID(word(n)) < 0)
            {
                FatalErrorInFunction
                    << "options." << key << ": no patch '" << n.c_str()
                    << "' in the mesh (constant/polyMesh/boundary has "
                    << mesh.boundaryMesh().names() << ")" << exit(FatalError);
            }
        }
    }

    // Euler time stepping is what makes the reported precursor balance exact
    void checkSchemes(const fvMesh& mesh) const
    {
        ITstream& is = mesh.ddtScheme("default");
        const word scheme(is);
        if (scheme != "Euler")
        {
            FatalErrorInFunction
                << "system/fvSchemes: ddtSchemes default must be Euler for cosimFoam "
                << "(the coupling exchanges one implicit step per coupling interval), got "
                << scheme << exit(FatalError);
        }
    }

    void prepare(const ParticleSet& particles) override
    {
        guarded("preparing the particles' placement", [&]
        {
            parcels_().prepare(particles.ids, particles.position, particles.radius);
        });
    }

    std::vector<std::size_t> place(const ParticleSet& all) override
    {
        return guarded("placing particles", [&]
        {
            const fvMesh& mesh = mesh_();
            Foam::cosim::ParcelDeposition& parcels = parcels_();
            // Decomposed: the master works on every parcel, the others on those it sends them
            ParticleSet received;
            const bool elsewhere = Pstream::parRun() && !Pstream::master();
            if (elsewhere)
            {
                parcels.routing().receive
                (
                    received.ids, received.position, received.radius, received.velocity
                );
            }
            else if (Pstream::parRun())
            {
                parcels.routing().send(all.ids, all.position, all.radius, all.velocity);
            }
            const ParticleSet& particles = elsewhere ? received : all;
            const label n = label(particles.size());
            parcels.place(particles.ids, particles.position, particles.radius);

            // Parcel volume per cell -> voidage, bounded below
            List<scalar> volume(n);
            for (label i = 0; i < n; ++i)
            {
                volume[i] = 4.0/3.0*constant::mathematical::pi*pow3(particles.radius[i]);
            }
            scalarField solid(mesh.nCells(), 0.0);
            parcels.deposit(volume, solid);
            scalarField& epsPlaced = epsPlaced_();
            epsPlaced = max(1.0 - solid/mesh.V().field(), settings_.min_voidage);

            particleVelocity_.setSize(n);
            for (label i = 0; i < n; ++i)
            {
                particleVelocity_[i] =
                    particles.velocity.size() == 3*particles.size()
                  ? vector
                    (
                        particles.velocity[3*i],
                        particles.velocity[3*i + 1],
                        particles.velocity[3*i + 2]
                    )
                  : vector::zero;
            }

            // Before the first step the parcels have always been there: no displacement flow
            // (after a resume the checkpoint's fields carry the last step's voidage instead)
            if (!advanced_ && !resumedOldTimes_)
            {
                volScalarField& eps = eps_();
                eps.primitiveFieldRef() = epsPlaced;
                eps.correctBoundaryConditions();
                eps.oldTime().primitiveFieldRef() = epsPlaced;
                eps.oldTime().correctBoundaryConditions();
                resetOldTime(epsRho_(), eps*rho_());
                if (settings_.species)
                {
                    resetOldTime(epsRhoY_(), epsRho_());
                }
            }

            std::vector<std::size_t> lost;
            for (label i = 0; i < n; ++i)
            {
                if (parcels.lost()[i])
                {
                    lost.push_back(std::size_t(i));
                }
            }
            return lost;
        });
    }

    static void resetOldTime(volScalarField& f, const tmp<volScalarField>& value)
    {
        const volScalarField v(value);
        f.primitiveFieldRef() = v.primitiveField();
        f.boundaryFieldRef() = v.boundaryField();
        f.oldTime().primitiveFieldRef() = v.primitiveField();
        f.oldTime().boundaryFieldRef() = v.boundaryField();
    }

    static void resetOldTime(volScalarField& f, const volScalarField& v)
    {
        resetOldTime(f, tmp<volScalarField>(new volScalarField(v)));
    }

    std::map<std::string, std::vector<double>> sample
    (
        const std::vector<std::string>& names
    ) const override
    {
        return guarded("sampling the gas at the particles", [&]
        {
            const fvMesh& mesh = mesh_();
            const Foam::cosim::ParcelDeposition& parcels = parcels_();
            const label n = parcels.size();
            const labelList& cell = parcels.centreCell();

            std::map<std::string, std::vector<double>> out;
            for (const std::string& name : names)
            {
                List<scalar> values;
                if (name == "fluid_velocity" || name == "pressure_gradient")
                {
                    // Average over the cells the parcel's volume went to, with the same
                    // weights as its K: the parcel feels K (u - v) and -V grad p exactly as
                    // the cells give them up (momentum conserved between gas and parcels)
                    List<vector> perParticle;
                    if (name == "fluid_velocity")
                    {
                        parcels.gatherAverage(U_().primitiveField(), perParticle);
                    }
                    else
                    {
                        const volVectorField gradp
                        (
                            Foam::cosim::bedConsistentGradient(p_(), resistance_())
                        );
                        parcels.gatherAverage(gradp.primitiveField(), perParticle);
                    }
                    values.setSize(3*n, 0.0);
                    for (label i = 0; i < n; ++i)
                    {
                        for (direction d = 0; d < 3; ++d)
                        {
                            values[3*i + d] = perParticle[i][d];
                        }
                    }
                }
                else if (name == "voidage")
                {
                    // Average over the cells the parcel's volume went to
                    parcels.gatherAverage(epsPlaced_(), values);
                }
                else if (name == "fluid_density" || name == "precursor_fraction"
                      || name == "fluid_viscosity" || name == "cell_size")
                {
                    if (name == "precursor_fraction" && !settings_.species)
                    {
                        throw ::cosim::InputError
                        (
                            "precursor_fraction was requested but the scene has no "
                            "mass transfer (Welcome.species is false)"
                        );
                    }
                    // The field read per cell, chosen once (not per particle)
                    const scalarField& perCell =
                        name == "fluid_density" ? rho_().primitiveField()
                      : name == "precursor_fraction" ? Y_().primitiveField()
                      : mesh.V().field();
                    const bool viscosity = (name == "fluid_viscosity");
                    const bool size = (name == "cell_size");
                    values.setSize(n, 0.0);
                    for (label i = 0; i < n; ++i)
                    {
                        const label c = cell[i];
                        if (c < 0)
                        {
                            continue;
                        }
                        values[i] =
                            viscosity ? mu_().value()
                          : size ? Foam::cbrt(perCell[c])
                          : perCell[c];
                    }
                }
                else
                {
                    throw ::cosim::InputError
                    (
                        "cosimFoam cannot sample field '" + name + "' (it provides "
                        "fluid_velocity, voidage, fluid_density, fluid_viscosity, "
                        "pressure_gradient, precursor_fraction, cell_size)"
                    );
                }
                parcels.sumOnMaster(values);  // the master answers for all processors
                out[name].assign(values.begin(), values.end());
            }
            return out;
        });
    }


    StepResult advance
    (
        double dt,
        const std::vector<double>& K,
        const std::vector<double>& k
    ) override
    {
        return guarded("advancing the gas", [&]
        {
            // Decomposed: the terms of the parcels each processor placed, from the master
            if (Pstream::parRun())
            {
                const Foam::cosim::ParcelRouting& routing = parcels_().routing();
                if (Pstream::master())
                {
                    routing.send(K, 1);
                    routing.send(k, 1);
                }
                else
                {
                    std::vector<double> myK, myk;
                    routing.receive(myK);
                    routing.receive(myk);
                    return step(dt, myK, myk);
                }
            }
            return step(dt, K, k);
        });
    }

    // One gas step over dt with the parcels' exchange terms (drag K and transfer k per parcel,
    // in the order the last Sample placed them): the terms into the cells, the PIMPLE loop of
    // the gas, the precursor, then what the step did.
    StepResult step(double dt, const std::vector<double>& Kp, const std::vector<double>& kp)
    {
        Time& runTime = runTime_();
        fvMesh& mesh = mesh_();
        pimpleControl& pimple = pimple_();

        checkTerms(dt, Kp, kp);
        runTime.setDeltaT(dt);
        ++runTime;

        volScalarField& p = p_();
        volVectorField& U = U_();
        volScalarField& rho = rho_();
        volScalarField& eps = eps_();
        volScalarField& epsRho = epsRho_();
        surfaceScalarField& phi = phi_();
        volScalarField& Kexchange = Kexchange_();
        volVectorField& KUp = KUp_();
        volScalarField& resistance = resistance_();
        const dimensionedScalar& psi = psi_();
        const dimensionedScalar& mu = mu_();
        const meshObjects::gravity& g = meshObjects::gravity::New(runTime);

        // Voidage of this step: the parcels as the last Sample placed them
        eps.primitiveFieldRef() = epsPlaced_();
        eps.correctBoundaryConditions();
        placeExchangeTerms(Kp, kp);

        const auto wall0 = std::chrono::steady_clock::now();
        logSolversThisStep();

        // --- PIMPLE
        while (pimple.loop())
        {
            if (pimple.firstIter())
            {
                rho = psi*p;
                epsRho = eps*rho;
            }

            #include "UEqn.H"

            while (pimple.correct())
            {
                #include "pEqn.H"
            }
        }

        #include "rhoEqn.H"

        StepResult result;
        gasThroughBoundaries(dt, result);
        if (settings_.species)
        {
            precursorStep(dt, kp, result);
        }

        rho = psi*p;
        describeStep(dt, result);
        result.solve_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

        runTime.write();
        advanced_ = true;
        return result;
    }

    // The exchange terms hold one value per parcel placed by the last Sample, and dt > 0.
    void checkTerms(double dt, const std::vector<double>& Kp, const std::vector<double>& kp) const
    {
        const label n = parcels_().size();
        if (!(dt > 0))
        {
            FatalErrorInFunction << "Advance dt must be > 0, got " << dt << exit(FatalError);
        }
        if (!Kp.empty() && label(Kp.size()) != n)
        {
            FatalErrorInFunction
                << "drag_coefficient has " << label(Kp.size()) << " values for " << n
                << " particles placed by the last Sample" << exit(FatalError);
        }
        if (!kp.empty() && label(kp.size()) != n)
        {
            FatalErrorInFunction
                << "transfer_coefficient has " << label(kp.size()) << " values for " << n
                << " particles placed by the last Sample" << exit(FatalError);
        }
    }

    // Exchange coefficients per cell volume: K and K u_p of the parcels into Kexchange and KUp,
    // the transfer coefficients k into the precursor's sink.
    void placeExchangeTerms(const std::vector<double>& Kp, const std::vector<double>& kp)
    {
        const fvMesh& mesh = mesh_();
        const Foam::cosim::ParcelDeposition& parcels = parcels_();
        const label n = parcels.size();
        volScalarField& Kexchange = Kexchange_();
        volVectorField& KUp = KUp_();
        const scalarField& V = mesh.V().field();
        scalarField Ksum(mesh.nCells(), 0.0);
        vectorField KvSum(mesh.nCells(), Zero);
        if (!Kp.empty())
        {
            List<scalar> K(n);
            List<vector> Kv(n);
            for (label i = 0; i < n; ++i)
            {
                K[i] = Kp[i];
                Kv[i] = Kp[i]*particleVelocity_[i];
            }
            parcels.deposit(K, Ksum);
            parcels.deposit(Kv, KvSum);
        }
        Kexchange.primitiveFieldRef() = Ksum/V;
        KUp.primitiveFieldRef() = KvSum/V;
        // Processor faces need the neighbour's values (face interpolation of A - K)
        Kexchange.correctBoundaryConditions();
        KUp.correctBoundaryConditions();
        if (settings_.species)
        {
            scalarField kSum(mesh.nCells(), 0.0);
            if (!kp.empty())
            {
                List<scalar> kList(n);
                forAll(kList, i)
                {
                    kList[i] = kp[i];
                }
                parcels.deposit(kList, kSum);
            }
            sinkCoeff_->primitiveFieldRef() = kSum/V;
            sinkCoeff_->correctBoundaryConditions();
        }
    }

    // The linear solvers' residual lines: every solver_log_every-th step only (a switch of
    // OpenFOAM's own, as DebugSwitches { SolverPerformance 0; } sets it for a whole run)
    void logSolversThisStep() const
    {
        if (settings_.solver_log_every > 1)
        {
            const int logged =
                runTime_().timeIndex() % settings_.solver_log_every == 0 ? 1 : 0;
            SolverPerformance<scalar>::debug = logged;
            SolverPerformance<vector>::debug = logged;
        }
    }

    // Gas mass through the boundaries [kg over the step] and held in the domain at its end
    void gasThroughBoundaries(double dt, StepResult& s) const
    {
        const fvMesh& mesh = mesh_();
        const surfaceScalarField& phi = phi_();
        scalar in = 0, out = 0;
        forAll(phi.boundaryField(), patchi)
        {
            if (mesh.boundary()[patchi].coupled())
            {
                continue;
            }
            for (const scalar f : phi.boundaryField()[patchi])
            {
                (f < 0 ? in : out) += mag(f)*dt;
            }
        }
        s.gas_mass_in = returnReduce(in, sumOp<scalar>());
        s.gas_mass_out = returnReduce(out, sumOp<scalar>());
        s.gas_mass_held = gSum(epsRho_().primitiveField()*mesh.V().field());
    }

    // The precursor over the step (YEqn.H) and its balance: what came in and left through the
    // boundaries, what the cells' sink took and what each parcel removed.
    void precursorStep(double dt, const std::vector<double>& kp, StepResult& result)
    {
        const fvMesh& mesh = mesh_();
        const Foam::cosim::ParcelDeposition& parcels = parcels_();
        const label n = parcels.size();
        const surfaceScalarField& phi = phi_();
        const volScalarField& epsRho = epsRho_();
        volScalarField& Y = Y_();
        volScalarField& epsRhoY = epsRhoY_();
        const volScalarField& sinkCoeff = sinkCoeff_();
        const dimensionedScalar Gamma("Gamma", mu_()/settings_.schmidt);
        const scalarField& V = mesh.V().field();

        const scalar heldStart =
            gSum(epsRhoY.oldTime().primitiveField()*Y.oldTime().primitiveField()*V);

        #include "YEqn.H"

        // Precursor through the boundaries, from the matrix's own face fluxes
        const tmp<surfaceScalarField> tflux = YEqn.flux();
        scalar in = 0, out = 0;
        forAll(tflux().boundaryField(), patchi)
        {
            if (mesh.boundary()[patchi].coupled())
            {
                continue;
            }
            for (const scalar f : tflux().boundaryField()[patchi])
            {
                (f < 0 ? in : out) += mag(f)*dt;
            }
        }

        // What each parcel removed: k_i dt sum_j w_ij Y(cell_j), the sink's own terms
        List<scalar> Yavg;
        parcels.gatherAverage(Y.primitiveField(), Yavg);
        parcels.sumOnMaster(Yavg);  // the master reports the parcels' removal
        result.precursor_removed.assign(std::size_t(n), 0.0);
        scalar removedTotal = 0;
        if (!kp.empty())
        {
            for (label i = 0; i < n; ++i)
            {
                result.precursor_removed[i] = kp[i]*dt*Yavg[i];
                removedTotal += result.precursor_removed[i];
            }
        }

        StepResult& s = result;
        s.species = true;
        s.precursor_in = returnReduce(in, sumOp<scalar>());
        s.precursor_out = returnReduce(out, sumOp<scalar>());
        s.precursor_held = gSum(epsRhoY.primitiveField()*Y.primitiveField()*V);
        s.precursor_held_start = heldStart;
        s.precursor_removed_cells =
            gSum(sinkCoeff.primitiveField()*Y.primitiveField()*V)*dt;
        s.precursor_removed_total = removedTotal;
        s.precursor_min = gMin(Y.primitiveField());
        s.precursor_max = gMax(Y.primitiveField());
    }

    // The step's pressure drop, Courant number and least voidage
    void describeStep(double dt, StepResult& s) const
    {
        const volScalarField& p = p_();
        const surfaceScalarField& phi = phi_();
        const volScalarField& epsRho = epsRho_();
        s.pressure_drop = patchAverage(p, settings_.inlet_patches)
                           - patchAverage(p, settings_.outlet_patches);
        {
            const scalarField sumPhi
            (
                fvc::surfaceSum(mag(phi))().primitiveField()
               /(epsRho.primitiveField()*mesh_().V().field())
            );
            s.max_courant = 0.5*gMax(sumPhi)*dt;
        }
        s.voidage_min = gMin(eps_().primitiveField());
    }

    // Area-weighted average of p over the named patches (NaN-free: 0 when none found)
    scalar patchAverage(const volScalarField& p, const std::vector<std::string>& names) const
    {
        const fvMesh& mesh = mesh_();
        scalar sum = 0, area = 0;
        forAll(mesh.boundary(), patchi)
        {
            if (!hasPatch(names, mesh.boundary()[patchi].name()))
            {
                continue;
            }
            const scalarField& a = mesh.magSf().boundaryField()[patchi];
            sum += Foam::sum(a*p.boundaryField()[patchi]);
            area += Foam::sum(a);
        }
        reduce(sum, sumOp<scalar>());
        reduce(area, sumOp<scalar>());
        return area > 0 ? sum/area : 0;
    }

    void writeNow() override
    {
        guarded("writing the fields", [&]
        {
            runTime_->writeNow();
            return 0;
        });
    }

    std::vector<std::string> checkpoint(const std::string& path) override
    {
        return guarded("writing a checkpoint", [&]
        {
            // The current time folder holds everything a restart needs, with the face
            // resistances of the last pressure solve (the parcels' pressure gradient of the
            // next Sample) and the old times of the next step's time derivatives (voidage,
            // eps rho); written in binary whatever the case's writeFormat, so that a resume
            // starts from the exact values; a copy goes to path
            const IOstream::streamFormat exact = IOstream::BINARY;
            const auto ver = IOstream::currentVersion;
            const auto cmp = IOstream::UNCOMPRESSED;
            runTime_->writeNow();
            if (runTime_->writeFormat() != exact)
            {
                runTime_->writeObject(exact, ver, cmp, true);
            }
            for (regIOobject* f : {static_cast<regIOobject*>(resistance_.get()),
                                   static_cast<regIOobject*>(epsRho_.get()),
                                   static_cast<regIOobject*>(epsRhoY_.get())})
            {
                if (f)
                {
                    f->instance() = runTime_->timeName();
                    f->writeObject(exact, ver, cmp, true);
                }
            }
            const fileName from = runTime_->timePath();
            fileName to = fileName(path);
            if (Pstream::parRun())
            {
                to = to/("processor" + Foam::name(Pstream::myProcNo()));
            }
            mkDir(to);
            to = to/runTime_->timeName();
            if (!cp(from, to))
            {
                FatalErrorInFunction
                    << "cannot copy " << from << " to " << to << exit(FatalError);
            }
            List<fileName> written(Pstream::nProcs());
            written[Pstream::myProcNo()] = to;
            Pstream::gatherList(written);
            return std::vector<std::string>(written.begin(), written.end());
        });
    }

    double time() const override
    {
        return runTime_->value();
    }
};


} // namespace cosim::foam


extern "C" ::cosim::foam::GasDomain* cosimFoamCreateGas
(
    int argc,
    char** argv,
    const ::cosim::foam::GasSettings* settings
)
{
    return new ::cosim::foam::FoamGasDomain(argc, argv, *settings);
}
